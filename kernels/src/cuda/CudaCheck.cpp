#include "cuda/CudaCheck.h"

#include <cuda_runtime_api.h>

#include <atomic>
#include <string>

namespace linkgi::cuda
{
void check(cudaError_t status, const char* what, const char* file, int line)
{
  if (status == cudaSuccess)
  {
    return;
  }
  cudaGetLastError(); // clear a non-sticky error, so the next call starts clean
  const bool oom = status == cudaErrorMemoryAllocation;
  std::string where = file;
  where = where.substr(where.find_last_of("/\\") + 1) + ":" + std::to_string(line);
  throw CudaError(std::string("CUDA error ") + cudaGetErrorName(status) + " (" +
      cudaGetErrorString(status) + ") in " + what + " at " + where +
      (oom ? "; the GPU is out of memory." : "."),
    oom);
}

void checkLaunch(const char* kernel, const char* file, int line)
{
  check(cudaGetLastError(), kernel, file, line);
}

namespace
{
std::atomic<std::size_t> allocationsLeft{ 0 };
}

cudaError_t allocate(void** pointer, std::size_t bytes)
{
  std::size_t left = allocationsLeft.load();
  while (left > 0 && !allocationsLeft.compare_exchange_weak(left, left - 1))
  {
  }
  return left == 1 ? cudaErrorMemoryAllocation : cudaMalloc(pointer, bytes);
}

void failAllocation(std::size_t n)
{
  allocationsLeft = n;
}

std::size_t allocationsBeforeFailure()
{
  return allocationsLeft.load();
}
}
