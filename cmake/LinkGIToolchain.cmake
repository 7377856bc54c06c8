# Compiler set-up shared by the three CMake projects that build LinkGI code: the top level,
# kernels/ on its own (the GPU machine) and paraview-plugin/ (ParaView's VTK). Macros, not
# functions: enable_language must run at directory scope.

# ccache for C and C++ (and CUDA, once enabled) when it is installed.
macro(linkgi_use_ccache)
  find_program(LINKGI_CCACHE ccache)
  if(LINKGI_CCACHE AND NOT CMAKE_CXX_COMPILER_LAUNCHER)
    set(CMAKE_C_COMPILER_LAUNCHER "${LINKGI_CCACHE}")
    set(CMAKE_CXX_COMPILER_LAUNCHER "${LINKGI_CCACHE}")
  endif()
endmacro()

# The option LINKGI_ENABLE_CUDA, defaulting to `default` (AUTO: on when nvcc is found; the
# CPU path always builds), and when on the CUDA language for one architecture (Hopper,
# sm_90, which keeps CI's compile time modest; set CMAKE_CUDA_ARCHITECTURES for others).
macro(linkgi_enable_cuda default)
  set(_linkgi_cuda_default ${default})
  if("${default}" STREQUAL "AUTO")
    if(NOT DEFINED CMAKE_CUDA_COMPILER AND EXISTS /usr/local/cuda/bin/nvcc)
      set(CMAKE_CUDA_COMPILER /usr/local/cuda/bin/nvcc)
    endif()
    include(CheckLanguage)
    check_language(CUDA)
    set(_linkgi_cuda_default OFF)
    if(CMAKE_CUDA_COMPILER)
      set(_linkgi_cuda_default ON)
    endif()
  endif()
  option(LINKGI_ENABLE_CUDA "Build the CUDA backend (needs nvcc; runs only where a GPU exists)"
    ${_linkgi_cuda_default})
  if(LINKGI_ENABLE_CUDA)
    if(NOT DEFINED CMAKE_CUDA_ARCHITECTURES)
      set(CMAKE_CUDA_ARCHITECTURES 90)
    endif()
    enable_language(CUDA)
    if(LINKGI_CCACHE AND NOT CMAKE_CUDA_COMPILER_LAUNCHER)
      set(CMAKE_CUDA_COMPILER_LAUNCHER "${LINKGI_CCACHE}")
    endif()
  endif()
endmacro()

# LINKGI_SANITIZE and LINKGI_FUZZ: sanitizer and libFuzzer builds (CI's build/sanitize-*).
include("${CMAKE_CURRENT_LIST_DIR}/LinkGISanitizers.cmake")
