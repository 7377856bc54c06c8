// CUDA errors become linkgi::CudaError exceptions that the solver reports (and, for
// out-of-memory, answers by falling back to the CPU); nothing aborts the process.
#pragma once

#include "cuda/Cuda.h"

#include <cuda_runtime_api.h>

#include <cstddef>
#include <string>

namespace linkgi::cuda
{
/// Throws CudaError for anything but cudaSuccess; `what` says what was being done.
void check(cudaError_t status, const char* what, const char* file, int line);

/// Checks a kernel launch (configuration errors) without waiting for the kernel.
void checkLaunch(const char* kernel, const char* file, int line);

/// cudaMalloc for GPUBuffer, the engine's one allocation of device memory, with the tests'
/// fault injection: after failAllocation(n) the n-th allocation from then on (1: the next)
/// fails as cudaMalloc does on a GPU out of memory. Test-only; 0 disarms it.
cudaError_t allocate(void** pointer, std::size_t bytes);
void failAllocation(std::size_t n);
/// The allocations left before the injected failure (0: it happened, or none was armed).
std::size_t allocationsBeforeFailure();
}

#define LINKGI_CUDA_CHECK(expr) ::linkgi::cuda::check((expr), #expr, __FILE__, __LINE__)
#define LINKGI_CUDA_CHECK_LAUNCH(name) ::linkgi::cuda::checkLaunch((name), __FILE__, __LINE__)
