# Where `cmake --install` puts LinkGI under CMAKE_INSTALL_PREFIX (paths relative to it).
# Included by the top-level CMakeLists.txt after GNUInstallDirs and find_package(Python3).
#
#   LINKGI_PYTHON_SITE_PACKAGES  the `linkgi` package's parent: a directory the prefix's
#                                Python reads, so `import linkgi` needs no PYTHONPATH
#   LINKGI_CMAKE_DESTINATION     LinkGIConfig.cmake and the exported targets
#   LINKGI_DOC_DESTINATION       README and the examples
#
# Each can be set on the command line; otherwise it follows the prefix, which is why the
# Debian package is built by a configure of its own with CMAKE_INSTALL_PREFIX=/usr
# (scripts/package.sh).

# Debian's Python (the one with VTK) reads <prefix>/lib/python3.X/dist-packages for
# /usr/local and /usr/lib/python3/dist-packages for the distribution's own packages, and no
# site-packages directory at all; other Pythons read their `posix_prefix` platlib. Python
# answers for itself, from the schemes it has.
if(NOT LINKGI_PYTHON_SITE_PACKAGES)
  string(REGEX REPLACE "/+$" "" _linkgi_prefix "${CMAKE_INSTALL_PREFIX}")
  execute_process(
    COMMAND "${Python3_EXECUTABLE}" -c [=[
import os, sys, sysconfig
prefix = sys.argv[1]
if 'deb_system' in sysconfig.get_scheme_names():
    # Debian: deb_system is /usr's layout; posix_local is /usr/local's, written as
    # {platbase}/local/lib/... with platbase /usr.
    scheme, root = ('deb_system', '/usr') if prefix == '/usr' else ('posix_local', '/usr/local')
    path = sysconfig.get_path('platlib', scheme, vars={'base': '/usr', 'platbase': '/usr'})
else:
    scheme, root = 'posix_prefix', prefix
    path = sysconfig.get_path('platlib', scheme, vars={'base': prefix, 'platbase': prefix})
print(os.path.relpath(path, root))
]=] "${_linkgi_prefix}"
    OUTPUT_VARIABLE _linkgi_site
    OUTPUT_STRIP_TRAILING_WHITESPACE
    RESULT_VARIABLE _linkgi_result)
  if(NOT _linkgi_result EQUAL 0 OR _linkgi_site STREQUAL "" OR IS_ABSOLUTE "${_linkgi_site}"
     OR _linkgi_site MATCHES "^\\.\\.")
    set(_linkgi_site "${CMAKE_INSTALL_LIBDIR}/python${Python3_VERSION_MAJOR}.")
    string(APPEND _linkgi_site "${Python3_VERSION_MINOR}/site-packages")
    message(WARNING "LinkGI: could not ask ${Python3_EXECUTABLE} where it reads packages; "
      "installing the Python package into ${_linkgi_site} (set LINKGI_PYTHON_SITE_PACKAGES).")
  endif()
  set(LINKGI_PYTHON_SITE_PACKAGES "${_linkgi_site}")
endif()

if(NOT LINKGI_CMAKE_DESTINATION)
  set(LINKGI_CMAKE_DESTINATION "${CMAKE_INSTALL_LIBDIR}/cmake/LinkGI")
endif()
if(NOT LINKGI_DOC_DESTINATION)
  set(LINKGI_DOC_DESTINATION "${CMAKE_INSTALL_DATAROOTDIR}/doc/linkgi")
endif()
message(STATUS "LinkGI: installs into ${CMAKE_INSTALL_PREFIX}: libraries in "
  "${CMAKE_INSTALL_LIBDIR}, Python package in ${LINKGI_PYTHON_SITE_PACKAGES}, CMake package in "
  "${LINKGI_CMAKE_DESTINATION}")
