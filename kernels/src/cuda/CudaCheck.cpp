#include "CudaCheck.h"

#include <cuda_runtime_api.h>

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
}
