// The solver's CUDA path: scene, BVH, links, light links and bounces resident on the GPU(s),
// recomputing only the stages the solver asks for. Host-facing: no device code here.
#pragma once

#include "DeviceBvh.h"
#include "Kernels.h"

#include "linkgi/Links.h"
#include "linkgi/Solver.h"
#include "linkgi/Topology.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace linkgi::cuda
{
/// Which stages the solver's change detection asks for (see Solver.cpp).
struct StageMask
{
  bool topology = true;  ///< triangles changed: rebuild the BVH, new topology
  bool positions = true; ///< vertices moved: refit or rebuild the BVH
  bool geometry = true;  ///< positions or normals changed: new shifts and face normals
  bool relink = true;    ///< links
  bool relight = true;   ///< light links
  bool materials = true; ///< albedo or emission
};

/// The host arrays of one update (owned by the solver).
struct HostInputs
{
  const Scene& scene;
  const Topology& topology;
  const std::vector<Vec3f>& shifts;
  const std::vector<Vec3f>& faceNormals;
};

/// A device matrix in the row-start / row-count form of CsrView. The entry buffers keep the
/// worst-case capacity (3 n_C or n_C per row), so GPUs can append rows without a merge.
struct DeviceCsr
{
  GPUBuffer<Index> rowStarts, rowCounts, columns;
  GPUBuffer<float> weights;
  Index nonZeros = 0;
  CsrView view() const;
  /// The bytes of the matrix itself (what a bounce reads), not the reserve.
  std::size_t usedBytes() const { return nonZeros * 8ull + rowStarts.size() * 8ull; }
};

/// One GPU's share of the work; the first device of the engine also holds everything after
/// the links (light links, bounces, output).
struct EngineDevice;

class Engine
{
public:
  /// Uses up to `maxDevices` devices (0 = all). Throws CudaError when none can be used.
  explicit Engine(int maxDevices);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  /// Runs the stages of `mask` (and always the bounces and smoothing); fills `solution`
  /// and the stage fields of `stats`. Throws CudaError or Aborted; after a throw the
  /// engine's caches are invalid and the next update must pass a full mask.
  void update(const HostInputs& in, const SolverOptions& options, const StageMask& mask,
    Solution& solution, SolverStats& stats, const ProgressCallback& progress);

  int deviceCount() const;
  /// "NVIDIA H100 80GB HBM3" or "2 x NVIDIA H200".
  std::string description() const;
  /// Largest GPU memory in use on any of the engine's devices, sampled after each stage.
  std::size_t peakBytes() const { return peak; }
  /// Elements each device linked in the last link stage.
  std::vector<std::size_t> linkedElements() const;
  /// Per device: batches and ms tracing, compressing and in all in the last link stage.
  void linkProfile(SolverStats& stats) const;
  /// The transport matrix W on the first device (for benchmarks).
  CsrView transport() const;

private:
  void uploadGeometry(const HostInputs& in, const StageMask& mask, SolverStats& stats,
    const SolverOptions& options);
  void buildLinks(const HostInputs& in, const SolverOptions& options, SolverStats& stats,
    const ProgressCallback& progress);
  void computeDirectLight(const HostInputs& in, const SolverOptions& options, SolverStats& stats);
  void bounceAndFinish(const HostInputs& in, const SolverOptions& options, Solution& solution,
    SolverStats& stats, const ProgressCallback& progress);
  void samplePeakMemory();
  /// work(device, index) on every device at once: the first on this thread, the others on
  /// their workers; rethrows the first exception after all have finished.
  void runOnAllDevices(const std::function<void(EngineDevice&, std::size_t)>& work);

  std::vector<std::unique_ptr<EngineDevice>> devices;
  std::string name;
  std::size_t peak = 0;
  std::uint64_t rawLinks = 0, rays = 0, lightRays = 0;
};
}
