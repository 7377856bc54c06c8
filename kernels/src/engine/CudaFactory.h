// Where the orchestrator gets the CUDA backend: the devices it may use and the method's
// CUDA implementation. By default cuda::devices and MethodSpec::createCuda; a test replaces
// them (ScopedCudaFactory) to make the backend's creation or one of its stages fail (no
// device, out of memory) on a machine without a GPU, and so test the CPU fallback there.
#pragma once

#include "engine/Pipeline.h"

#include <functional>
#include <memory>
#include <string>

namespace linkgi::engine
{
struct CudaFactory
{
  /// The number of usable CUDA devices; when 0, `why` says why not.
  std::function<std::size_t(std::string* why)> devices;
  /// The CUDA implementation of `spec`; throws CudaError when it cannot be made.
  std::function<std::unique_ptr<MethodBackend>(const MethodSpec& spec, const SolverOptions& options)> create;
  /// Whether `spec` has a CUDA implementation at all (MethodSpec::hasCudaBackend); empty: it
  /// has (a test's factory makes one for every method).
  std::function<bool(const MethodSpec& spec)> has;
};

/// The factory in use.
const CudaFactory& cudaFactory();

/// Replaces the factory for its lifetime (tests only; not thread safe against updates
/// running meanwhile).
class ScopedCudaFactory
{
public:
  explicit ScopedCudaFactory(CudaFactory replacement);
  ~ScopedCudaFactory();
  ScopedCudaFactory(const ScopedCudaFactory&) = delete;
  ScopedCudaFactory& operator=(const ScopedCudaFactory&) = delete;

private:
  CudaFactory previous;
};
}
