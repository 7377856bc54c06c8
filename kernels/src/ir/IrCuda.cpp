// Instant radiosity on the GPU: not written yet. The orchestrator turns this CudaError into
// a warning and runs the update on the CPU backend.
#include "ir/IrBackends.h"

#include "linkgi/Cuda.h"

namespace linkgi::ir
{
std::unique_ptr<engine::MethodBackend> createCudaBackend(const SolverOptions&)
{
  throw CudaError("The instant-radiosity method has no CUDA backend yet; it runs on the CPU.", false);
}
}
