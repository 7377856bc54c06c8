// The CUDA backend as the rest of the engine sees it: which devices exist, a GPU ray
// tracer behind the RayTracer interface, and the error type. No CUDA headers here; builds
// without CUDA implement these as "no device".
#pragma once

#include "linkgi/Error.h"
#include "shared/RayTracer.h"

#include <memory>
#include <string>
#include <vector>

namespace linkgi
{
/// A CUDA error, with the call that failed. outOfMemory() tells the solver to fall back to
/// the CPU rather than give up.
class CudaError : public Error
{
public:
  CudaError(const std::string& message, bool outOfMemory)
    : Error(message), oom(outOfMemory)
  {
  }
  bool outOfMemory() const { return oom; }

private:
  bool oom;
};

namespace cuda
{
struct DeviceInfo
{
  int index = 0;
  std::string name;
  int computeMajor = 0, computeMinor = 0;
  int multiprocessors = 0;
  std::size_t totalBytes = 0;
};

/// True if this build contains the CUDA backend (whether or not a GPU is present).
bool compiled();

/// The CUDA devices the backend can use (compute capability 7.0 or newer). Empty when the
/// build has no CUDA backend or the machine no usable device; `why` then says which.
std::vector<DeviceInfo> devices(std::string* why = nullptr);

/// A RayTracer on one GPU: build/refit on the device, trace()/occluded() copy the rays
/// there and the results back (for tools and tests; the solver keeps its data on the GPU).
/// Throws CudaError when the device cannot be used.
std::unique_ptr<RayTracer> createRayTracer(int device = 0);
}
}
