# linkgi_python_package(<build dir> <install destination> <component>): the pure-Python
# files of the `linkgi` package, and vtk.js's offline viewer for linkgi.export_html, into
# <build dir> (beside the wrapped modules) and installed to <install destination>. Used for
# Debian's VTK (cmake/LinkGIInstall.cmake) and for ParaView's (paraview-plugin/).
#
# The viewer comes from the trame-vtk wheel (BSD licence, shipped beside it) that
# scripts/setup.sh downloads from PyPI; without it linkgi.export_html needs trame-vtk.
get_filename_component(_linkgi_package_source "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
set(LINKGI_TRAME_VTK_WHEEL "${_linkgi_package_source}/build/downloads/trame_vtk-2.11.17-py3-none-any.whl"
  CACHE FILEPATH "The trame-vtk wheel whose vtk.js viewer linkgi.export_html inlines")

function(linkgi_python_package directory destination component)
  set(files)
  foreach(file IN ITEMS __init__.py export.py pyvista.py web.py _gltf.py _vtkjs.py)
    configure_file("${_linkgi_package_source}/Wrapping/Python/linkgi/${file}"
      "${directory}/${file}" COPYONLY)
    list(APPEND files "${directory}/${file}")
  endforeach()
  if(EXISTS "${LINKGI_TRAME_VTK_WHEEL}")
    set(unpacked "${CMAKE_BINARY_DIR}/trame-vtk")
    file(ARCHIVE_EXTRACT INPUT "${LINKGI_TRAME_VTK_WHEEL}" DESTINATION "${unpacked}"
      PATTERNS "trame_vtk/tools/static_viewer.html" "*/licenses/LICENSE")
    file(GLOB license "${unpacked}/*/licenses/LICENSE")
    configure_file("${unpacked}/trame_vtk/tools/static_viewer.html"
      "${directory}/vtkjs_viewer.html" COPYONLY)
    configure_file("${license}" "${directory}/vtkjs_viewer.LICENSE" COPYONLY)
    list(APPEND files "${directory}/vtkjs_viewer.html" "${directory}/vtkjs_viewer.LICENSE")
  else()
    message(WARNING "LinkGI: ${LINKGI_TRAME_VTK_WHEEL} not found (scripts/setup.sh downloads "
      "it): linkgi.export_html will need trame-vtk installed")
  endif()
  install(FILES ${files} DESTINATION "${destination}" COMPONENT "${component}")
endfunction()
