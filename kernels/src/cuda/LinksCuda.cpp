// The link-structure method's CUDA backend, as its MethodSpec creates it.
#include "CudaEngine.h"

namespace linkgi::links
{
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions& options)
{
  return std::make_unique<cuda::Engine>(options.cudaDevices);
}
}
