# SPDX-License-Identifier: BSD-3-Clause
# The VTK-free kernels. Every pipeline stage keeps its math in <Stage>/Kernel/ and declares it
# with av_add_kernel(). A kernel is compiled on its own (an OBJECT library) and sees only its
# own headers and those of the kernels it names in DEPENDS, so the stage layering is checked by
# the compiler; all kernels are then linked into one shared library, AnisoVoronoiKernels, which
# the VTK modules, the applications and the tests link.

# Third-party libraries of the kernels (Debian packages, see scripts/setup.sh).
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(TBB REQUIRED)
find_path(CHOLMOD_INCLUDE_DIR cholmod.h PATH_SUFFIXES suitesparse REQUIRED)
find_library(CHOLMOD_LIBRARY cholmod REQUIRED)
find_path(TETGEN_INCLUDE_DIR tetgen.h REQUIRED)
find_library(TETGEN_LIBRARY NAMES tet REQUIRED)
find_path(LBFGSPP_INCLUDE_DIR LBFGS.h REQUIRED)
find_path(NANOFLANN_INCLUDE_DIR nanoflann.hpp REQUIRED)
# hypre (BoomerAMG) for the embedding's iterative global solve; Debian builds it with MPI.
find_path(HYPRE_INCLUDE_DIR HYPRE.h PATH_SUFFIXES hypre REQUIRED)
find_library(HYPRE_LIBRARY HYPRE REQUIRED)
find_package(MPI REQUIRED COMPONENTS C)

set_property(GLOBAL PROPERTY AV_KERNELS "")
set_property(GLOBAL PROPERTY AV_KERNEL_INTERFACES "")
set_property(GLOBAL PROPERTY AV_KERNEL_TEST_DIRS "")

# av_add_kernel(<Name> [DEPENDS <kernel>...])
# Adds the kernel of the calling folder: every *.cxx in it, its headers public to the kernels
# that depend on it, and one CTest driver for its Testing/Test*.cxx (see av_add_cxx_tests).
function(av_add_kernel name)
  cmake_parse_arguments(PARSE_ARGV 1 arg "" "" "DEPENDS")
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/*.cxx)
  # Headers and link dependencies of the kernel, for the kernels and tests that use it.
  add_library(av_kernel_${name} INTERFACE)
  set_property(GLOBAL APPEND PROPERTY AV_KERNEL_INTERFACES av_kernel_${name})
  target_include_directories(av_kernel_${name} INTERFACE
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}>)
  foreach(dep IN LISTS arg_DEPENDS)
    target_link_libraries(av_kernel_${name} INTERFACE av_kernel_${dep})
  endforeach()
  target_link_libraries(av_kernel_${name} INTERFACE Eigen3::Eigen)
  if(sources)
    add_library(av_kernel_${name}_objects OBJECT ${sources})
    target_link_libraries(av_kernel_${name}_objects PRIVATE av_kernel_${name} TBB::tbb)
    target_include_directories(av_kernel_${name}_objects SYSTEM PRIVATE
      ${CHOLMOD_INCLUDE_DIR} ${TETGEN_INCLUDE_DIR} ${LBFGSPP_INCLUDE_DIR} ${NANOFLANN_INCLUDE_DIR})
    target_compile_definitions(av_kernel_${name}_objects PRIVATE TETLIBRARY)
    target_compile_features(av_kernel_${name}_objects PUBLIC cxx_std_17)
    set_target_properties(av_kernel_${name}_objects PROPERTIES POSITION_INDEPENDENT_CODE ON)
    if(CMAKE_BUILD_TYPE STREQUAL "Release")
      target_compile_options(av_kernel_${name}_objects PRIVATE -O3)
    endif()
    set_property(GLOBAL APPEND PROPERTY AV_KERNELS ${name})
  endif()
  if(BUILD_TESTING AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/Testing)
    # The tests are built once the library exists (av_finish_kernels).
    set_property(GLOBAL APPEND PROPERTY AV_KERNEL_TEST_DIRS "${name}|${CMAKE_CURRENT_SOURCE_DIR}/Testing")
  endif()
endfunction()

# Links every kernel added so far into AnisoVoronoiKernels and adds the kernel tests.
function(av_finish_kernels)
  get_property(kernels GLOBAL PROPERTY AV_KERNELS)
  get_property(interfaces GLOBAL PROPERTY AV_KERNEL_INTERFACES)
  set(objects)
  foreach(k IN LISTS kernels)
    list(APPEND objects $<TARGET_OBJECTS:av_kernel_${k}_objects>)
  endforeach()
  add_library(AnisoVoronoiKernels SHARED ${objects})
  foreach(k IN LISTS kernels)
    target_link_libraries(AnisoVoronoiKernels PUBLIC av_kernel_${k})
  endforeach()
  target_link_libraries(AnisoVoronoiKernels PRIVATE TBB::tbb ${CHOLMOD_LIBRARY} ${TETGEN_LIBRARY}
    ${HYPRE_LIBRARY} MPI::MPI_C)
  target_compile_features(AnisoVoronoiKernels PUBLIC cxx_std_17)
  if(NOT AV_KERNELS_ONLY)
    # The VTK modules link it, so it joins their export set.
    install(TARGETS AnisoVoronoiKernels ${interfaces} EXPORT AnisoVoronoi
      LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
      RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  endif()
  get_property(test_dirs GLOBAL PROPERTY AV_KERNEL_TEST_DIRS)
  foreach(entry IN LISTS test_dirs)
    string(REPLACE "|" ";" entry "${entry}")
    list(GET entry 0 name)
    list(GET entry 1 dir)
    av_add_cxx_tests(PREFIX Kernel.${name} DIRECTORY ${dir} LABELS kernel ${name}
      LINK AnisoVoronoiKernels TBB::tbb ${CHOLMOD_LIBRARY}
      INCLUDES ${CHOLMOD_INCLUDE_DIR})
  endforeach()
endfunction()
