# The libraries skein builds against, all from Debian 12 packages (scripts/install-deps.sh).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenMesh REQUIRED)            # target OpenMeshCore (no namespace)
find_package(assimp REQUIRED)              # target assimp::assimp
find_package(CLI11 REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(spdlog REQUIRED)
find_package(OpenMP REQUIRED)
find_package(TBB REQUIRED)
find_package(PNG REQUIRED)
find_package(TinyGLTF REQUIRED)              # libtinygltf-dev 2.7: glTF 2.0 tube meshes, target TinyGLTF::TinyGLTF
find_package(MPI REQUIRED COMPONENTS CXX)  # Open MPI 4.1 (libopenmpi-dev): skein-mpi, target MPI::MPI_CXX

# OpenSubdiv 3.5 (libosd-dev): its CMake config points at a missing libosdCPU.a, so find it by hand.
find_path(OPENSUBDIV_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)
find_library(OPENSUBDIV_CPU_LIBRARY osdCPU REQUIRED)
add_library(skein_opensubdiv INTERFACE IMPORTED)
target_include_directories(skein_opensubdiv INTERFACE ${OPENSUBDIV_INCLUDE_DIR})
target_link_libraries(skein_opensubdiv INTERFACE ${OPENSUBDIV_CPU_LIBRARY})
add_library(OpenSubdiv::osdCPU ALIAS skein_opensubdiv)
