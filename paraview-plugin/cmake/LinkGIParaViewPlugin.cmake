# Included by the top-level CMakeLists.txt: builds the ParaView plugin (paraview-plugin/) as a
# CMake build of its own in <build>/paraview-plugin, because ParaView's VTK 9.2 cannot be
# found in the top-level configure, which holds the system VTK 9.1.
#
# LINKGI_BUILD_PARAVIEW_PLUGIN: AUTO (the default) builds it when ParaView 5.11's CMake
# package, pvbatch and ParaView's Python modules (python3-paraview, which scripts/setup.sh
# unpacks into build/python3-paraview) are found; ON requires them; OFF skips it.
#
# Sets, for Testing/ParaView:
#   LINKGI_PARAVIEW_PLUGIN_ENABLED  whether the plugin is built
#   LINKGI_PARAVIEW_PLUGIN_FILE     the plugin library, for LoadPlugin()
#   LINKGI_PVBATCH                  pvbatch
#   LINKGI_PARAVIEW_PYTHONPATH      the PYTHONPATH that pvbatch needs
#   LINKGI_PARAVIEW_PLUGIN_INSTALL_DIR  where `cmake --install` puts LinkGI/ and LinkGI.xml,
#                                   relative to the prefix

set(LINKGI_BUILD_PARAVIEW_PLUGIN AUTO CACHE STRING
  "Build the ParaView plugin against ParaView's own VTK (AUTO: when ParaView 5.11 is found)")
set_property(CACHE LINKGI_BUILD_PARAVIEW_PLUGIN PROPERTY STRINGS AUTO ON OFF)
set(LINKGI_PARAVIEW_PYTHON_PREFIX "${PROJECT_SOURCE_DIR}/build/python3-paraview" CACHE PATH
  "Where python3-paraview is unpacked (scripts/setup.sh --paraview-python)")

set(LINKGI_PARAVIEW_PLUGIN_ENABLED OFF)
if(NOT LINKGI_BUILD_PARAVIEW_PLUGIN STREQUAL "OFF")
  # Found without find_package(ParaView), which would load a second VTK into this configure.
  find_path(LINKGI_PARAVIEW_CMAKE_DIR paraview-config.cmake
    PATH_SUFFIXES
      "lib/cmake/paraview-5.11"
      "lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/paraview-5.11"
    DOC "Directory of ParaView's paraview-config.cmake")
  find_program(LINKGI_PVBATCH pvbatch)
  set(_linkgi_missing)
  if(NOT LINKGI_PARAVIEW_CMAKE_DIR)
    list(APPEND _linkgi_missing "ParaView 5.11's CMake package (paraview-dev)")
  endif()
  if(NOT LINKGI_PVBATCH)
    list(APPEND _linkgi_missing "pvbatch (paraview)")
  endif()
  # ParaView's Python modules and wrapping hierarchy files: unpacked, or installed.
  set(LINKGI_PARAVIEW_PYTHONPATH "${LINKGI_PARAVIEW_PYTHON_PREFIX}/usr/lib/python3/dist-packages")
  if(NOT EXISTS "${LINKGI_PARAVIEW_PYTHONPATH}/paraview/simple.py")
    if(EXISTS "/usr/lib/python3/dist-packages/paraview/simple.py")
      set(LINKGI_PARAVIEW_PYTHONPATH "/usr/lib/python3/dist-packages")
    else()
      list(APPEND _linkgi_missing
        "python3-paraview (run scripts/setup.sh --paraview-python to unpack it into ${LINKGI_PARAVIEW_PYTHON_PREFIX})")
    endif()
  endif()
  if(NOT _linkgi_missing)
    set(LINKGI_PARAVIEW_PLUGIN_ENABLED ON)
  elseif(LINKGI_BUILD_PARAVIEW_PLUGIN STREQUAL "ON")
    message(FATAL_ERROR "LINKGI_BUILD_PARAVIEW_PLUGIN is ON but these are missing: ${_linkgi_missing}")
  else()
    message(STATUS "LinkGI: not building the ParaView plugin; missing: ${_linkgi_missing}")
  endif()
endif()

if(LINKGI_PARAVIEW_PLUGIN_ENABLED)
  include(ExternalProject)
  set(_linkgi_plugin_build "${CMAKE_BINARY_DIR}/paraview-plugin")
  set(LINKGI_PARAVIEW_PLUGIN_FILE
    "${_linkgi_plugin_build}/${CMAKE_INSTALL_LIBDIR}/paraview-5.11/plugins/LinkGI/LinkGI.so")
  set(_linkgi_launcher_args)
  if(CMAKE_CXX_COMPILER_LAUNCHER)
    list(APPEND _linkgi_launcher_args
      "-DCMAKE_C_COMPILER_LAUNCHER:FILEPATH=${CMAKE_C_COMPILER_LAUNCHER}"
      "-DCMAKE_CXX_COMPILER_LAUNCHER:FILEPATH=${CMAKE_CXX_COMPILER_LAUNCHER}")
  endif()
  # The engine with the same backends as here (and so the same objects, from ccache).
  set(_linkgi_cuda_args "-DLINKGI_ENABLE_CUDA:BOOL=${LINKGI_ENABLE_CUDA}")
  if(LINKGI_ENABLE_CUDA)
    list(APPEND _linkgi_cuda_args
      "-DCMAKE_CUDA_COMPILER:FILEPATH=${CMAKE_CUDA_COMPILER}"
      "-DCMAKE_CUDA_ARCHITECTURES:STRING=${CMAKE_CUDA_ARCHITECTURES}")
    if(CMAKE_CUDA_COMPILER_LAUNCHER)
      list(APPEND _linkgi_cuda_args
        "-DCMAKE_CUDA_COMPILER_LAUNCHER:FILEPATH=${CMAKE_CUDA_COMPILER_LAUNCHER}")
    endif()
  endif()
  ExternalProject_Add(linkgi_paraview_plugin
    SOURCE_DIR        "${PROJECT_SOURCE_DIR}/paraview-plugin"
    BINARY_DIR        "${_linkgi_plugin_build}"
    PREFIX            "${CMAKE_BINARY_DIR}/CMakeFiles/linkgi_paraview_plugin"
    CMAKE_GENERATOR   "${CMAKE_GENERATOR}"
    CMAKE_CACHE_ARGS
      "-DCMAKE_BUILD_TYPE:STRING=${CMAKE_BUILD_TYPE}"
      "-DCMAKE_C_COMPILER:FILEPATH=${CMAKE_C_COMPILER}"
      "-DCMAKE_CXX_COMPILER:FILEPATH=${CMAKE_CXX_COMPILER}"
      ${_linkgi_launcher_args}
      ${_linkgi_cuda_args}
      "-DCMAKE_INSTALL_LIBDIR:STRING=${CMAKE_INSTALL_LIBDIR}"
      "-DParaView_DIR:PATH=${LINKGI_PARAVIEW_CMAKE_DIR}"
      "-DLINKGI_PARAVIEW_PYTHON_PREFIX:PATH=${LINKGI_PARAVIEW_PYTHON_PREFIX}"
    # The plugin compiles sources of this tree (Filters/, Rendering/, kernels/): let its own
    # ninja decide what is out of date on every build (a no-op costs well under a second).
    BUILD_ALWAYS      ON
    # After the engine: the plugin's copy of it then comes out of ccache.
    DEPENDS           linkgi_kernels
    INSTALL_COMMAND   ""
    USES_TERMINAL_CONFIGURE ON
    USES_TERMINAL_BUILD     ON
    BUILD_BYPRODUCTS  "${LINKGI_PARAVIEW_PLUGIN_FILE}")

  # `cmake --install` of this build installs the plugin too (component `paraview`), where
  # ParaView keeps its plugins: <prefix>/<libdir>/paraview-5.11/plugins/LinkGI/, plus the
  # plugin list LinkGI.xml beside that directory. It runs the plugin build's own install
  # script with this install's prefix and DESTDIR, restricted to its `paraview` component:
  # the script also has rules for the client-server archives (`development`), which are
  # linked into LinkGI.so and have no use installed.
  set(LINKGI_PARAVIEW_PLUGIN_INSTALL_DIR "${CMAKE_INSTALL_LIBDIR}/paraview-5.11/plugins")
  install(CODE "
    set(_linkgi_component \"\${CMAKE_INSTALL_COMPONENT}\")
    set(CMAKE_INSTALL_COMPONENT paraview)
    include(\"${_linkgi_plugin_build}/cmake_install.cmake\")
    set(CMAKE_INSTALL_COMPONENT \"\${_linkgi_component}\")"
    COMPONENT paraview)
endif()
