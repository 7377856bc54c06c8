// The link-structure method's CUDA backend, as its MethodSpec creates it.
#include "methods/links/cuda/CudaEngine.h"

namespace linkgi::links
{
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions& options)
{
  return std::make_unique<cuda::Engine>(options.cudaDevices);
}
}
