# The libraries skein builds against, all from Debian 12 packages (scripts/install-deps.sh).
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenMesh REQUIRED)            # target OpenMeshCore (no namespace)
find_package(assimp REQUIRED)              # target assimp::assimp
find_package(CLI11 REQUIRED)
find_package(nlohmann_json REQUIRED)
find_package(spdlog REQUIRED)
find_package(TBB REQUIRED)
find_package(PNG REQUIRED)
