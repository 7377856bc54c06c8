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

# The package's Python modules: in the build tree beside the wrapped modules (so the build
# works with PYTHONPATH=<build>/${LINKGI_PYTHON_SITE_PACKAGES}), and installed with them.
set(linkgi_python_files __init__.py export.py _gltf.py _vtkjs.py)
foreach(_linkgi_file IN LISTS linkgi_python_files)
  configure_file("Wrapping/Python/linkgi/${_linkgi_file}"
    "${CMAKE_BINARY_DIR}/${LINKGI_PYTHON_SITE_PACKAGES}/linkgi/${_linkgi_file}" COPYONLY)
  install(FILES "Wrapping/Python/linkgi/${_linkgi_file}"
    DESTINATION "${LINKGI_PYTHON_SITE_PACKAGES}/linkgi"
    COMPONENT   python)
endforeach()

# linkgi.export_html's page is vtk.js's offline viewer, taken from the trame-vtk wheel
# (BSD licence, shipped beside it) that scripts/setup.sh downloads from PyPI.
set(LINKGI_TRAME_VTK_WHEEL "${PROJECT_SOURCE_DIR}/build/downloads/trame_vtk-2.11.17-py3-none-any.whl"
  CACHE FILEPATH "The trame-vtk wheel whose vtk.js viewer linkgi.export_html inlines")
if(EXISTS "${LINKGI_TRAME_VTK_WHEEL}")
  set(_linkgi_viewer_dir "${CMAKE_BINARY_DIR}/trame-vtk")
  file(ARCHIVE_EXTRACT INPUT "${LINKGI_TRAME_VTK_WHEEL}" DESTINATION "${_linkgi_viewer_dir}"
    PATTERNS "trame_vtk/tools/static_viewer.html" "*/licenses/LICENSE")
  file(GLOB _linkgi_viewer_license "${_linkgi_viewer_dir}/*/licenses/LICENSE")
  set(_linkgi_site "${CMAKE_BINARY_DIR}/${LINKGI_PYTHON_SITE_PACKAGES}/linkgi")
  configure_file("${_linkgi_viewer_dir}/trame_vtk/tools/static_viewer.html"
    "${_linkgi_site}/vtkjs_viewer.html" COPYONLY)
  configure_file("${_linkgi_viewer_license}" "${_linkgi_site}/vtkjs_viewer.LICENSE" COPYONLY)
  install(FILES "${_linkgi_site}/vtkjs_viewer.html" "${_linkgi_site}/vtkjs_viewer.LICENSE"
    DESTINATION "${LINKGI_PYTHON_SITE_PACKAGES}/linkgi"
    COMPONENT   python)
else()
  message(WARNING "LinkGI: ${LINKGI_TRAME_VTK_WHEEL} not found (scripts/setup.sh downloads "
    "it): linkgi.export_html will need trame-vtk installed")
endif()

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
