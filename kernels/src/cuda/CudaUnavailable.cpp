// The CUDA entry points of builds without the CUDA backend (LINKGI_ENABLE_CUDA=OFF).
#include "cuda/Cuda.h"

#include "methods/ir/IrBackends.h"
#include "methods/iv/IvBackends.h"
#include "methods/pm/PmBackends.h"
#include "methods/links/LinksBackends.h"

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

namespace linkgi::links
{
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions&)
{
  throw CudaError("This build has no CUDA backend; reconfigure with LINKGI_ENABLE_CUDA=ON.", false);
}
}

namespace linkgi::ir
{
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions&)
{
  throw CudaError("This build has no CUDA backend; reconfigure with LINKGI_ENABLE_CUDA=ON.", false);
}

std::vector<Vec3f> gatherCuda(const Scene&, const VplSet&, const GatherParams&, bool)
{
  throw CudaError("This build has no CUDA backend; reconfigure with LINKGI_ENABLE_CUDA=ON.", false);
}
}

namespace linkgi::iv
{
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions&)
{
  throw CudaError("This build has no CUDA backend; reconfigure with LINKGI_ENABLE_CUDA=ON.", false);
}
}

namespace linkgi::pm
{
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions&)
{
  throw CudaError("This build has no CUDA backend; reconfigure with LINKGI_ENABLE_CUDA=ON.", false);
}

void buildTreeOnDevice(const std::vector<Vec3f>&, std::vector<Index>&, std::vector<std::uint8_t>&)
{
  throw CudaError("This build has no CUDA backend; reconfigure with LINKGI_ENABLE_CUDA=ON.", false);
}
}
