# SPDX-License-Identifier: BSD-3-Clause
# The one test convention of the project (VTK's own):
# - C++: every Testing/Test<Name>.cxx (kernels) or Testing/Cxx/Test<Name>.cxx (VTK classes)
#   defines `int Test<Name>(int argc, char* argv[])`, checks with the AV_CHECK* macros of
#   Testing/Core/AnisoTestChecks.h and returns AV_TEST_RESULT(). One driver executable per
#   folder runs them (create_test_sourcelist); argv[1] is Data/, argv[2] a scratch folder.
# - Python: every Testing/Python/Test<Name>.py runs with the system Python 3.11 (ParaView's
#   vtkmodules) and exits non-zero on failure; plugin tests run under pvbatch.
# CTest names are <Kind>.<Stage>.Test<Name>, with the kind and the stage as labels, so that
# `ctest -L kernel` runs every VTK-free test and `ctest -L Embedding` one stage.

set(AV_TEST_DATA_DIR ${PROJECT_SOURCE_DIR}/Data)
set(AV_TEST_TEMP_DIR ${CMAKE_BINARY_DIR}/Testing/Temporary)

# av_add_cxx_tests(PREFIX <Kind.Stage> DIRECTORY <dir> LABELS <label>...
#                  LINK <target>... [INCLUDES <dir>...])
function(av_add_cxx_tests)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "PREFIX;DIRECTORY" "LABELS;LINK;INCLUDES")
  file(GLOB tests RELATIVE ${arg_DIRECTORY} CONFIGURE_DEPENDS ${arg_DIRECTORY}/Test*.cxx)
  if(NOT tests)
    return()
  endif()
  string(REPLACE "." "" driver "${arg_PREFIX}Tests")
  create_test_sourcelist(driver_sources ${driver}.cxx ${tests})
  list(TRANSFORM tests PREPEND ${arg_DIRECTORY}/ OUTPUT_VARIABLE test_paths)
  add_executable(${driver} ${CMAKE_CURRENT_BINARY_DIR}/${driver}.cxx ${test_paths})
  target_link_libraries(${driver} PRIVATE ${arg_LINK})
  target_include_directories(${driver} PRIVATE ${PROJECT_SOURCE_DIR}/Testing/Core)
  target_include_directories(${driver} SYSTEM PRIVATE ${arg_INCLUDES})
  foreach(src IN LISTS tests)
    get_filename_component(name ${src} NAME_WE)
    add_test(NAME ${arg_PREFIX}.${name}
      COMMAND ${driver} ${name} ${AV_TEST_DATA_DIR} ${AV_TEST_TEMP_DIR})
    set_tests_properties(${arg_PREFIX}.${name} PROPERTIES LABELS "${arg_LABELS}" TIMEOUT 600)
  endforeach()
endfunction()

# av_add_python_tests(PREFIX <Kind.Stage> DIRECTORY <dir> LABELS <label>...)
function(av_add_python_tests)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "PREFIX;DIRECTORY" "LABELS")
  file(GLOB tests CONFIGURE_DEPENDS ${arg_DIRECTORY}/Test*.py)
  foreach(src IN LISTS tests)
    get_filename_component(name ${src} NAME_WE)
    add_test(NAME ${arg_PREFIX}.${name} COMMAND ${AV_PYTHON3} ${src})
    set_tests_properties(${arg_PREFIX}.${name} PROPERTIES LABELS "python;${arg_LABELS}" TIMEOUT 600
      ENVIRONMENT "${AV_TEST_ENVIRONMENT}")
  endforeach()
endfunction()

# av_add_vtk_stage_tests(<Stage>): the C++ and Python tests of a stage's VTK classes, called
# from the stage's module CMakeLists (Filters/<Stage>/Testing/{Cxx,Python}).
function(av_add_vtk_stage_tests stage module)
  if(NOT BUILD_TESTING)
    return()
  endif()
  av_add_cxx_tests(PREFIX Vtk.${stage} DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/Testing/Cxx
    LABELS vtk ${stage}
    LINK ${module} AnisoVoronoiKernels ${AV_VTK_TEST_MODULES}
    INCLUDES ${PROJECT_SOURCE_DIR}/Testing/Cxx)
  av_add_python_tests(PREFIX Python.${stage} DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/Testing/Python
    LABELS ${stage})
endfunction()
