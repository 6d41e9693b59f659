# cuda/ builds on the yarn engine alone (core/relax, issue 23): no header or host source of it may reach, through
# any chain of includes, OpenMesh, OpenSubdiv, assimp or a header of core/stitchmesh, core/surface or
# core/workflow. Run by ctest (cuda_includes_no_stitch_mesh) with CXX, SOURCE, GENERATED and EIGEN set.
file(GLOB sources ${SOURCE}/cuda/*.hpp ${SOURCE}/cuda/*.cpp)
set(forbidden "OpenMesh|opensubdiv|assimp|/core/stitchmesh/|/core/surface/|/core/workflow/")
set(checked 0)
foreach(source ${sources})
  execute_process(COMMAND ${CXX} -std=c++20 -M -x c++ -I${SOURCE}/core -I${SOURCE} -I${GENERATED} -isystem ${EIGEN} ${source}
                  OUTPUT_VARIABLE deps ERROR_VARIABLE errors RESULT_VARIABLE status)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${source}: the preprocessor failed:\n${errors}")
  endif()
  string(REGEX MATCHALL "[^ \\\n]*(${forbidden})[^ \\\n]*" found "${deps}")
  if(found)
    list(REMOVE_DUPLICATES found)
    list(JOIN found "\n  " found)
    message(FATAL_ERROR "${source} includes, directly or not:\n  ${found}\nThe CUDA relaxer may only use the yarn engine (core/relax) and core/common.")
  endif()
  math(EXPR checked "${checked} + 1")
endforeach()
if(checked EQUAL 0)
  message(FATAL_ERROR "no source of cuda/ found under ${SOURCE}")
endif()
message(STATUS "${checked} sources of cuda/ include no mesh, surface, stitch-mesh or workflow header")
