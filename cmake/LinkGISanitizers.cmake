# Sanitizer and fuzzing builds, included by LinkGIToolchain.cmake (so the top level and
# kernels/ alone both have them). CI builds them as separate trees under build/sanitize-*
# and build/fuzz (Testing/Sanitize); by hand:
#   cmake -S . -B build-asan -G Ninja -DLINKGI_SANITIZE=address,undefined
#   cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_C_COMPILER=clang
#     -DLINKGI_SANITIZE=address,undefined -DLINKGI_FUZZ=ON
#
# LINKGI_SANITIZE: a comma-separated -fsanitize list for every C and C++ file and link of
# the project ("address,undefined" or "thread"), empty for none. Any report is an error:
# undefined behaviour aborts instead of printing and going on.
# LINKGI_FUZZ (Clang only): coverage instrumentation for libFuzzer everywhere, and the fuzz
# targets of Testing/Fuzz.
set(LINKGI_SANITIZE "" CACHE STRING
  "Sanitizers for every LinkGI file: address,undefined or thread (empty: none)")
option(LINKGI_FUZZ "Instrument for libFuzzer and build the fuzz targets (Clang)" OFF)

if(LINKGI_SANITIZE AND NOT _linkgi_sanitizers_applied)
  # Once per project, though every configure of kernels/ and the top level includes it.
  set(_linkgi_sanitizers_applied ON)
  set(_linkgi_sanitize_flags -fsanitize=${LINKGI_SANITIZE} -fno-omit-frame-pointer -g)
  if(LINKGI_SANITIZE MATCHES "undefined")
    list(APPEND _linkgi_sanitize_flags -fno-sanitize-recover=undefined)
    # GCC leaves it out of "undefined": a float to int conversion that overflows is as
    # undefined as an integer overflow (a NaN coordinate turned into a grid cell).
    list(APPEND _linkgi_sanitize_flags -fsanitize=float-cast-overflow)
  endif()
  add_compile_options("$<$<COMPILE_LANGUAGE:C,CXX>:${_linkgi_sanitize_flags}>")
  add_link_options("$<$<LINK_LANGUAGE:C,CXX>:-fsanitize=${LINKGI_SANITIZE}>")
endif()
if(LINKGI_FUZZ AND NOT _linkgi_fuzz_applied)
  set(_linkgi_fuzz_applied ON)
  add_compile_options("$<$<COMPILE_LANGUAGE:C,CXX>:-fsanitize=fuzzer-no-link>")
endif()
