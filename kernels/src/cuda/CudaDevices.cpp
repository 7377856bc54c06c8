#include "cuda/Cuda.h"

#include <cuda_runtime_api.h>

namespace linkgi::cuda
{
bool compiled()
{
  return true;
}

std::vector<DeviceInfo> devices(std::string* why)
{
  std::vector<DeviceInfo> out;
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess)
  {
    cudaGetLastError();
    if (why)
    {
      *why = std::string("no usable CUDA device (") + cudaGetErrorString(status) + ")";
    }
    return out;
  }
  for (int d = 0; d < count; ++d)
  {
    cudaDeviceProp prop{};
    if (cudaGetDeviceProperties(&prop, d) != cudaSuccess || prop.major < 7)
    {
      cudaGetLastError();
      continue;
    }
    DeviceInfo info;
    info.index = d;
    info.name = prop.name;
    info.computeMajor = prop.major;
    info.computeMinor = prop.minor;
    info.multiprocessors = prop.multiProcessorCount;
    info.totalBytes = prop.totalGlobalMem;
    out.push_back(info);
  }
  if (out.empty() && why)
  {
    *why = count ? "no CUDA device of compute capability 7.0 or newer" : "no CUDA device";
  }
  return out;
}
}
