// CUDA errors become linkgi::CudaError exceptions that the solver reports (and, for
// out-of-memory, answers by falling back to the CPU); nothing aborts the process.
#pragma once

#include "linkgi/Cuda.h"

#include <cuda_runtime_api.h>

#include <string>

namespace linkgi::cuda
{
/// Throws CudaError for anything but cudaSuccess; `what` says what was being done.
void check(cudaError_t status, const char* what, const char* file, int line);

/// Checks a kernel launch (configuration errors) without waiting for the kernel.
void checkLaunch(const char* kernel, const char* file, int line);
}

#define LINKGI_CUDA_CHECK(expr) ::linkgi::cuda::check((expr), #expr, __FILE__, __LINE__)
#define LINKGI_CUDA_CHECK_LAUNCH(name) ::linkgi::cuda::checkLaunch((name), __FILE__, __LINE__)
