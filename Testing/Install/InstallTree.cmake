# `cmake --install` of the build into a fresh prefix, then checks what a user of the prefix
# relies on: the files of each part are there, and no installed file refers to the build
# tree (a path into it would break once the build is gone, or on another machine).
#
# Usage: cmake -DBUILD_DIR=<build> -DPREFIX=<prefix> -DLIB_DIR=<rel> -DPYTHON_SITE=<rel>
#              -DCMAKE_DIR=<rel> -DDOC_DIR=<rel> -DPLUGIN_DIR=<rel> -P InstallTree.cmake
# (directories relative to the prefix; PLUGIN_DIR empty: no plugin)
foreach(var BUILD_DIR PREFIX LIB_DIR PYTHON_SITE CMAKE_DIR DOC_DIR)
  if(NOT ${var})
    message(FATAL_ERROR "InstallTree.cmake: ${var} is not set")
  endif()
endforeach()

file(REMOVE_RECURSE "${PREFIX}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${PREFIX}"
  OUTPUT_VARIABLE output ERROR_VARIABLE output RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${result}):\n${output}")
endif()

set(expected
  "include/linkgi/vtkGlobalIlluminationFilter.h"
  "include/linkgi/vtkGlobalIlluminationMapper.h"
  "${LIB_DIR}/libLinkGIFiltersGlobalIllumination.so"
  "${LIB_DIR}/libLinkGIRenderingGlobalIllumination.so"
  "${CMAKE_DIR}/LinkGIConfig.cmake"
  "${CMAKE_DIR}/LinkGIConfigVersion.cmake"
  "${CMAKE_DIR}/LinkGI-targets.cmake"
  "${PYTHON_SITE}/linkgi/__init__.py"
  "${DOC_DIR}/examples/Cxx/CMakeLists.txt"
  "${DOC_DIR}/examples/Python/sphere_on_plane.py")
file(GLOB python_modules "${PREFIX}/${PYTHON_SITE}/linkgi/LinkGIFiltersGlobalIllumination*.so")
if(NOT python_modules)
  message(FATAL_ERROR "no wrapped module LinkGIFiltersGlobalIllumination in ${PYTHON_SITE}/linkgi")
endif()
if(PLUGIN_DIR)
  list(APPEND expected "${PLUGIN_DIR}/LinkGI.xml" "${PLUGIN_DIR}/LinkGI/LinkGI.so")
endif()
foreach(file IN LISTS expected)
  if(NOT EXISTS "${PREFIX}/${file}")
    message(FATAL_ERROR "the install lacks ${file}")
  endif()
endforeach()
# Only what ParaView loads goes with the plugin: its client-server archives are linked in.
file(GLOB_RECURSE archives RELATIVE "${PREFIX}" "${PREFIX}/*.a")
if(archives)
  message(FATAL_ERROR "static archives installed: ${archives}")
endif()

# Text and binaries alike (the RPATHs, strings compiled in). The prefix itself lies in the
# build tree here, so this also finds an absolute path into the prefix: the install must
# work wherever it is moved.
execute_process(COMMAND grep -rlF "${BUILD_DIR}" "${PREFIX}"
  OUTPUT_VARIABLE referring RESULT_VARIABLE result)
if(result EQUAL 0)
  message(FATAL_ERROR "installed files refer to the build tree ${BUILD_DIR}:\n${referring}")
elseif(NOT result EQUAL 1)
  message(FATAL_ERROR "grep failed (${result})")
endif()
file(GLOB_RECURSE installed RELATIVE "${PREFIX}" "${PREFIX}/*")
list(LENGTH installed count)
message(STATUS "ok: ${count} files installed into ${PREFIX}, none refers to ${BUILD_DIR}")
