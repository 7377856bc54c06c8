# Install rules beyond what vtk_module_build and vtk_module_wrap_python write themselves
# (libraries, headers, exported targets, Python modules): the `linkgi` package's
# __init__.py, the CMake package (LinkGIConfig.cmake), README and examples. Included by the
# top-level CMakeLists.txt after the modules are built and wrapped; the ParaView plugin's
# install is in paraview-plugin/cmake/LinkGIParaViewPlugin.cmake, the Debian package in
# cmake/LinkGIPackaging.cmake.
#
# Components: runtime (libraries), python, development (headers, CMake files), examples;
# paraview (the plugin).

include(CMakePackageConfigHelpers)

# The package's Python files beside the wrapped modules (so the build works with
# PYTHONPATH=<build>/${LINKGI_PYTHON_SITE_PACKAGES}), and installed with them.
include(cmake/LinkGIPythonPackage.cmake)
linkgi_python_package("${CMAKE_BINARY_DIR}/${LINKGI_PYTHON_SITE_PACKAGES}/linkgi"
  "${LINKGI_PYTHON_SITE_PACKAGES}/linkgi" python)

# find_package(LinkGI): the VTK version and the VTK modules that the LinkGI modules' public
# interfaces use, read from the modules themselves.
set(LINKGI_VTK_VERSION "${VTK_VERSION_MAJOR}.${VTK_VERSION_MINOR}")
set(LINKGI_VTK_COMPONENTS)
foreach(_linkgi_module IN LISTS linkgi_modules)
  vtk_module_get_property("${_linkgi_module}" PROPERTY INTERFACE_vtk_module_depends
    VARIABLE _linkgi_depends)
  foreach(_linkgi_depend IN LISTS _linkgi_depends)
    if(_linkgi_depend MATCHES "^VTK::(.+)$")
      list(APPEND LINKGI_VTK_COMPONENTS "${CMAKE_MATCH_1}")
    endif()
  endforeach()
endforeach()
list(REMOVE_DUPLICATES LINKGI_VTK_COMPONENTS)
list(SORT LINKGI_VTK_COMPONENTS)
list(JOIN LINKGI_VTK_COMPONENTS " " LINKGI_VTK_COMPONENTS)
set(LINKGI_PARAVIEW_PLUGIN_CONFIG "${CMAKE_INSTALL_LIBDIR}/paraview-5.11/plugins/LinkGI.xml")

configure_package_config_file(cmake/LinkGIConfig.cmake.in
  "${CMAKE_BINARY_DIR}/${LINKGI_CMAKE_DESTINATION}/LinkGIConfig.cmake"
  INSTALL_DESTINATION "${LINKGI_CMAKE_DESTINATION}"
  PATH_VARS LINKGI_PYTHON_SITE_PACKAGES LINKGI_PARAVIEW_PLUGIN_CONFIG)
# 0.x: a new minor version may change the API.
write_basic_package_version_file(
  "${CMAKE_BINARY_DIR}/${LINKGI_CMAKE_DESTINATION}/LinkGIConfigVersion.cmake"
  VERSION       "${PROJECT_VERSION}"
  COMPATIBILITY SameMinorVersion)
install(FILES
    "${CMAKE_BINARY_DIR}/${LINKGI_CMAKE_DESTINATION}/LinkGIConfig.cmake"
    "${CMAKE_BINARY_DIR}/${LINKGI_CMAKE_DESTINATION}/LinkGIConfigVersion.cmake"
  DESTINATION "${LINKGI_CMAKE_DESTINATION}"
  COMPONENT   development)

# README and the examples, sources only (the scenes are generated in code: there is no
# example data). Examples/Cxx builds on its own against the installed package.
install(FILES README.md DESTINATION "${LINKGI_DOC_DESTINATION}" COMPONENT examples)
install(DIRECTORY Examples/Cxx Examples/Python
  DESTINATION "${LINKGI_DOC_DESTINATION}/examples"
  COMPONENT   examples)
