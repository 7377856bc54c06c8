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
    // Without CUDA in the build no method has a backend, and devices() says the build's why.
    [](const MethodSpec& spec) { return !cuda::compiled() || spec.hasCudaBackend(); }
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
