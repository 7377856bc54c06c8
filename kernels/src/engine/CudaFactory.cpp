#include "engine/CudaFactory.h"

#include "cuda/Cuda.h"

namespace linkgi::engine
{
namespace
{
CudaFactory& current()
{
  static CudaFactory factory{
    [](std::string* why) { return cuda::devices(why).size(); },
    [](const MethodSpec& spec, const SolverOptions& options) { return spec.createCuda(options); },
    [](const MethodSpec& spec) { return spec.hasCudaBackend(); }
  };
  return factory;
}
}

const CudaFactory& cudaFactory()
{
  return current();
}

ScopedCudaFactory::ScopedCudaFactory(CudaFactory replacement) : previous(current())
{
  current() = std::move(replacement);
}

ScopedCudaFactory::~ScopedCudaFactory()
{
  current() = std::move(previous);
}
}
