# Debian packages through CPack, from a build configured with CMAKE_INSTALL_PREFIX=/usr
# (scripts/package.sh does all of it):
#
#   linkgi_<version>_amd64.deb           the VTK modules, `import linkgi`, headers, the CMake
#                                        package, README and examples
#   linkgi-paraview_<version>_amd64.deb  the ParaView 5.11 plugin (a package of its own, so
#                                        that VTK and Python users do not pull in ParaView)
#
# Depends: dpkg-shlibdeps reads what the libraries link (libvtk9.1, libembree3-3, libtbb12,
# paraview for the plugin, libc6, ...); added by hand is what Python imports and no library
# links: python3-vtk9 and the Python the modules are built for. OpenMesh is not named: no
# LinkGI library links it. CUDA neither: its runtime is linked in statically and the driver
# is opened at run time, if there is one (else the CPU backend runs).
#
# Included last by the top-level CMakeLists.txt, once every install rule exists.

set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "linkgi")
set(CPACK_PACKAGE_VENDOR "LinkGI")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_CONTACT "LinkGI Dev <dev@linkgi.invalid>")
set(CPACK_PACKAGING_INSTALL_PREFIX "${CMAKE_INSTALL_PREFIX}")
set(CPACK_PACKAGE_DIRECTORY "${CMAKE_BINARY_DIR}/packages")
# cpack refuses a build configured for another prefix: its layout is that prefix's (under
# /usr/local the Python package goes where Debian's Python reads it only under /usr/local).
set(CPACK_PROJECT_CONFIG_FILE "${CMAKE_BINARY_DIR}/CPackLinkGI.cmake")
if(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  file(WRITE "${CPACK_PROJECT_CONFIG_FILE}" "")
else()
  file(WRITE "${CPACK_PROJECT_CONFIG_FILE}" "message(FATAL_ERROR \"LinkGI: this build installs \"
  \"into ${CMAKE_INSTALL_PREFIX}; build the Debian packages with scripts/package.sh (a build \"
  \"configured with -DCMAKE_INSTALL_PREFIX=/usr).\")\n")
endif()

# Two packages, one per component group (without the plugin, only linkgi).
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL runtime python development examples)
if(LINKGI_PARAVIEW_PLUGIN_ENABLED)
  list(APPEND CPACK_COMPONENTS_ALL paraview)
endif()
set(CPACK_COMPONENTS_GROUPING ONE_PER_GROUP)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Where dpkg-shlibdeps finds the libraries that the packages hold themselves (their
# build-tree copies): the LinkGI modules, and the plugin's own, beside LinkGI.so.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS
  "${CMAKE_BINARY_DIR}/paraview-plugin/${CMAKE_INSTALL_LIBDIR}/paraview-5.11/plugins/LinkGI"
  "${CMAKE_BINARY_DIR}/lib")

# The wrapped modules are built for one minor version of Python and of VTK.
math(EXPR _linkgi_vtk_next "${VTK_VERSION_MINOR} + 1")
math(EXPR _linkgi_python_next "${Python3_VERSION_MINOR} + 1")
set(CPACK_DEBIAN_LINKGI_PACKAGE_NAME "linkgi")
set(CPACK_DEBIAN_LINKGI_PACKAGE_DEPENDS "\
python3-vtk9 (>= ${VTK_VERSION_MAJOR}.${VTK_VERSION_MINOR}), \
python3-vtk9 (<< ${VTK_VERSION_MAJOR}.${_linkgi_vtk_next}), \
python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}), \
python3 (<< ${Python3_VERSION_MAJOR}.${_linkgi_python_next})")
# find_package(LinkGI) finds VTK's CMake package.
set(CPACK_DEBIAN_LINKGI_PACKAGE_SUGGESTS "libvtk9-dev")
# The first line is the summary; CPack indents the rest.
set(CPACK_DEBIAN_LINKGI_DESCRIPTION "per-vertex multi-bounce global illumination for VTK
The VTK filter vtkGlobalIlluminationFilter traces a link structure between mesh
vertices and bounces light over it (direct and indirect irradiance, radiance);
vtkGlobalIlluminationMapper draws the result with shadow-mapped direct light.
For C++ (find_package(LinkGI)) and Python (import linkgi, with python3-vtk9).")
set(CPACK_DEBIAN_PARAVIEW_PACKAGE_NAME "linkgi-paraview")
# Depends on paraview: from its shlibs, for the exact upstream version the plugin is built with.
set(CPACK_DEBIAN_PARAVIEW_DESCRIPTION "global illumination plugin for ParaView 5.11
A Global Illumination representation, filter and scene source for ParaView:
per-vertex multi-bounce diffuse light with shadow maps, from the view's lights.
Load it by name (paraview --plugins=LinkGI), or have ParaView list and load it:
PV_PLUGIN_CONFIG_FILE=/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/paraview-5.11/plugins/LinkGI.xml")

include(CPack)
cpack_add_component_group(linkgi)
cpack_add_component_group(paraview)
cpack_add_component(runtime GROUP linkgi)
cpack_add_component(python GROUP linkgi DEPENDS runtime)
cpack_add_component(development GROUP linkgi DEPENDS runtime)
cpack_add_component(examples GROUP linkgi)
cpack_add_component(paraview GROUP paraview)
