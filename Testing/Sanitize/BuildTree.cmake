# Configures (once) and builds a tree of its own for a ctest test: the sanitizer and fuzzing
# builds under <build>/sanitize-*, like the Debian package test's build of its own. Two ctest
# runs in one build tree wait for each other here instead of building into one directory at
# once.
#   cmake -DSOURCE=<dir> -DBUILD=<dir> -DGENERATOR=<gen> -DOPTIONS=<a|b|...>
#         -DTARGETS=<a|b|...> -P BuildTree.cmake
# OPTIONS and TARGETS are separated by "|" (a ";" list would be split by add_test).
foreach(var SOURCE BUILD GENERATOR TARGETS)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "BuildTree.cmake needs -D${var}=")
  endif()
endforeach()
string(REPLACE "|" ";" options "${OPTIONS}")
string(REPLACE "|" ";" targets "${TARGETS}")

file(MAKE_DIRECTORY "${BUILD}")
file(LOCK "${BUILD}.lock" GUARD PROCESS TIMEOUT 3600)

function(run)
  string(REPLACE ";" " " shown "${ARGN}")
  message(STATUS "+ ${shown}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${shown}: ${result}")
  endif()
endfunction()

# Options given again on every run: a changed test definition reconfigures the tree.
run(${CMAKE_COMMAND} -S "${SOURCE}" -B "${BUILD}" -G "${GENERATOR}" ${options})
cmake_host_system_information(RESULT cores QUERY NUMBER_OF_LOGICAL_CORES)
run(${CMAKE_COMMAND} --build "${BUILD}" -j ${cores} --target ${targets})
