// The CUDA plumbing's entry points in builds without it (LINKGI_ENABLE_CUDA=OFF). The methods
// need nothing here: without CUDA they do not override MethodSpec::createCuda.
#include "cuda/Cuda.h"

namespace linkgi::cuda
{
bool compiled()
{
  return false;
}

std::vector<DeviceInfo> devices(std::string* why)
{
  if (why)
  {
    *why = "this build has no CUDA backend (LINKGI_ENABLE_CUDA=OFF)";
  }
  return {};
}

std::unique_ptr<RayTracer> createRayTracer(int)
{
  throw CudaError("This build has no CUDA backend; reconfigure with LINKGI_ENABLE_CUDA=ON.", false);
}
}
