# find_package(ParaView) on Debian 12 without python3-paraview.
#
# paraview-dev's CMake package also exports what python3-paraview installs (pvpython, the
# Python extension modules), and each exported targets file stops the configure with
# "references the file ... but this file does not exist" when one of its files is missing.
# python3-paraview cannot be installed beside python3-vtk9 (scripts/setup.sh unpacks it
# into the build tree instead), and the plugin uses none of those files. So, before
# find_package, every targets file that points at missing files is loaded from a copy
# without that check (paths still resolved against the original location); ParaView's
# own include of it then finds its targets defined and returns at once.

# Loads `targets_file` like include(), minus the check that the imported files exist.
function(_linkgi_include_without_file_check targets_file)
  file(READ "${targets_file}" content)
  set(check "if(NOT EXISTS \"\${_cmake_file}\")")
  string(FIND "${content}" "${check}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "LinkGI: unexpected layout of ${targets_file}; install python3-paraview "
      "or pass -DLINKGI_BUILD_PARAVIEW_PLUGIN=OFF.")
  endif()
  get_filename_component(dir "${targets_file}" DIRECTORY)
  get_filename_component(name "${targets_file}" NAME)
  string(REPLACE "${check}" "if(FALSE)" content "${content}")
  string(REPLACE "\${CMAKE_CURRENT_LIST_FILE}" "${targets_file}" content "${content}")
  string(REPLACE "\${CMAKE_CURRENT_LIST_DIR}" "${dir}" content "${content}")
  set(copy "${CMAKE_BINARY_DIR}/CMakeFiles/linkgi-paraview-targets/${name}")
  file(WRITE "${copy}" "${content}")
  include("${copy}")
endfunction()

# True in `out` when a configuration file of `targets_file` imports a file that is missing.
function(_linkgi_targets_file_incomplete targets_file prefix out)
  get_filename_component(dir "${targets_file}" DIRECTORY)
  get_filename_component(base "${targets_file}" NAME_WE)
  file(GLOB config_files "${dir}/${base}-*.cmake")
  foreach(config_file IN LISTS config_files)
    file(STRINGS "${config_file}" lines REGEX "IMPORTED_LOCATION_[A-Z]+ ")
    foreach(line IN LISTS lines)
      string(REGEX REPLACE ".*IMPORTED_LOCATION_[A-Z]+ \"\\\${_IMPORT_PREFIX}(/[^\"]*)\".*" "\\1"
        location "${line}")
      if(NOT EXISTS "${prefix}${location}")
        set(${out} TRUE PARENT_SCOPE)
        return()
      endif()
    endforeach()
  endforeach()
  set(${out} FALSE PARENT_SCOPE)
endfunction()

# Finds ParaView `version` with the components listed after it (asking for components also
# keeps find_package from requiring the Qt development packages of ParaView's GUI modules).
macro(linkgi_find_paraview version)
  find_path(LINKGI_PARAVIEW_CMAKE_DIR paraview-config.cmake
    HINTS "${ParaView_DIR}"
    PATH_SUFFIXES
      "lib/cmake/paraview-${version}"
      "lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/paraview-${version}"
    DOC "Directory of ParaView's paraview-config.cmake")
  if(LINKGI_PARAVIEW_CMAKE_DIR)
    # The install prefix: <prefix>/lib[/<arch>]/cmake/paraview-X.Y, as the targets files
    # compute it.
    get_filename_component(_linkgi_prefix "${LINKGI_PARAVIEW_CMAKE_DIR}/../../.." ABSOLUTE)
    if(CMAKE_LIBRARY_ARCHITECTURE AND LINKGI_PARAVIEW_CMAKE_DIR MATCHES "/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/")
      get_filename_component(_linkgi_prefix "${_linkgi_prefix}/.." ABSOLUTE)
    endif()
    # VTK's first: ParaView's targets refer to some of them.
    file(GLOB _linkgi_vtk_targets_files "${LINKGI_PARAVIEW_CMAKE_DIR}/vtk/*-targets.cmake")
    file(GLOB _linkgi_targets_files "${LINKGI_PARAVIEW_CMAKE_DIR}/*-targets.cmake")
    foreach(_linkgi_file IN LISTS _linkgi_vtk_targets_files _linkgi_targets_files)
      _linkgi_targets_file_incomplete("${_linkgi_file}" "${_linkgi_prefix}" _linkgi_incomplete)
      if(_linkgi_incomplete)
        message(STATUS "LinkGI: ${_linkgi_file} imports files that are not installed "
          "(python3-paraview); loading it without the check")
        _linkgi_include_without_file_check("${_linkgi_file}")
      endif()
    endforeach()
    set(ParaView_DIR "${LINKGI_PARAVIEW_CMAKE_DIR}" CACHE PATH "ParaView's CMake package" FORCE)
  endif()
  find_package(ParaView ${version} REQUIRED COMPONENTS ${ARGN})
endmacro()

# The wrappers of ParaView's VTK modules need their hierarchy files, which Debian ships in
# python3-paraview, not in paraview-dev. Points each module's hierarchy at the copy under
# `prefix` (python3-paraview unpacked by scripts/setup.sh) where the installed one is
# missing.
function(linkgi_use_unpacked_hierarchies prefix)
  # Every module that find_package imported into this directory (VTK:: and ParaView::).
  get_property(modules DIRECTORY "${CMAKE_CURRENT_SOURCE_DIR}" PROPERTY IMPORTED_TARGETS)
  set(moved 0)
  foreach(module IN LISTS modules)
    if(NOT TARGET "${module}")
      continue()
    endif()
    get_property(hierarchy TARGET "${module}" PROPERTY "INTERFACE_vtk_module_hierarchy")
    if(hierarchy AND NOT EXISTS "${hierarchy}" AND EXISTS "${prefix}${hierarchy}")
      set_property(TARGET "${module}" PROPERTY "INTERFACE_vtk_module_hierarchy" "${prefix}${hierarchy}")
      math(EXPR moved "${moved} + 1")
    endif()
  endforeach()
  get_property(hierarchy TARGET VTK::CommonCore PROPERTY "INTERFACE_vtk_module_hierarchy")
  if(NOT EXISTS "${hierarchy}")
    message(FATAL_ERROR "LinkGI: ParaView's wrapping hierarchy files (in python3-paraview) are "
      "missing: run scripts/setup.sh --paraview-python, or set LINKGI_PARAVIEW_PYTHON_PREFIX "
      "to where python3-paraview is unpacked.")
  endif()
  if(moved)
    message(STATUS "LinkGI: ${moved} wrapping hierarchy files taken from ${prefix}")
  endif()
endfunction()
