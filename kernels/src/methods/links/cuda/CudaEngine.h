// The link-structure method's CUDA backend: scene, BVH, links, light links and bounces
// resident on the GPU(s); the orchestrator (Solver.cpp) says which stages to run. Host-facing:
// no device code here.
#pragma once

#include "cuda/DeviceBvh.h"
#include "cuda/Kernels.h"

#include "engine/Pipeline.h"
#include "methods/links/LinksBackends.h"

#include "methods/links/Links.h"
#include "cuda/DetailKernels.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace linkgi::cuda
{
/// A block of rows of a device matrix, in the row-start / row-count form of CsrView.
struct DeviceCsr
{
  GPUBuffer<Offset> rowStarts;
  GPUBuffer<Index> rowCounts, columns;
  GPUBuffer<float> weights;
  Offset nonZeros = 0;
  CsrView view(Index firstElement, int lanes) const;
  /// The bytes of the matrix itself (what a bounce reads).
  std::size_t usedBytes() const { return nonZeros * 8ull + rowStarts.size() * 12ull; }
};

/// One partition of the work (a GPU, or a share of one); the first also holds everything
/// that needs the whole mesh (topology, light links, smoothing, output).
struct EngineDevice;

/// What one link batch cost: elements [first, first + count) in `ms` of its GPU's tracing.
struct BatchCost
{
  Index first = 0, count = 0;
  double ms = 0.0;
};

/// Boundaries b_0 = 0 < ... < b_parts = elements of contiguous ranges of about equal cost,
/// from the batches of the last link stage over the same elements (their cost spread evenly
/// over each batch's elements); empty when they do not cover [0, elements) exactly.
std::vector<Index> equalCostSplit(std::vector<BatchCost> last, Index elements, std::size_t parts);

class Engine final : public engine::MethodBackend
{
public:
  /// Uses up to `maxDevices` devices (0 = all), one partition each; the environment variable
  /// LINKGI_CUDA_PARTITIONS=P makes P partitions, dealt round-robin over those devices (several
  /// on one GPU: how the multi-GPU paths are tested on one). Throws CudaError when no device
  /// can be used.
  explicit Engine(int maxDevices);
  ~Engine() override;
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  /// Runs one of the stages of links::Stage. Throws CudaError or Aborted; after a throw the
  /// engine's caches are lost (discard() says so) and the next update runs every stage.
  void run(std::size_t stage, const engine::StageContext& context) override;
  void commit() override {}
  bool discard() override { return false; }
  void describe(SolverStats& stats) const override;
  const RayTracer* sceneTracer() const override { return meshTracer.get(); }

  int deviceCount() const;
  /// "NVIDIA H100 80GB HBM3" or "2 x NVIDIA H200".
  std::string description() const;
  /// Rows of W each partition holds (= elements it linked in the last link stage).
  std::vector<std::size_t> linkedElements() const;
  /// Per partition: batches and ms tracing, compressing and in all in the last link stage.
  void linkProfile(SolverStats& stats) const;
  /// The transport matrix W, when it is one block on the first partition (for benchmarks).
  CsrView transport() const;

private:
  void updateGeometry(const engine::StageContext& c);
  void buildLinks(const engine::StageContext& c);
  void computeDirectLight(const engine::StageContext& c);
  void bounceAndFinish(const engine::StageContext& c);
  /// Copies, for every partition q in `to` (all, or the first only), the rows of buffer
  /// `of` that the other partitions computed, once their work queued so far is done.
  void exchange(Rgba* (*of)(EngineDevice&), bool toAll);
  /// work(device, index) on every device at once: the first on this thread, the others on
  /// their workers; rethrows the first exception after all have finished.
  void runOnAllDevices(const std::function<void(EngineDevice&, std::size_t)>& work);

  std::vector<std::unique_ptr<EngineDevice>> devices;
  std::unique_ptr<RayTracer> meshTracer; ///< the first partition's BVH, for checks of a result
  Index edgeCount = 0; ///< of the topology on the first partition
  float eps = 0.f; ///< rayEpsilon of the positions (the ray origins' bound), set by the geometry stage
  std::string name;
  int physicalDevices = 0;
  /// Every partition is the same kind of GPU (the same model, or shares of one): the next
  /// link stage then splits the elements by the last one's cost, one range per partition.
  bool identicalDevices = false;
  std::vector<BatchCost> lastBatches; ///< of the last link stage, over all partitions
  std::uint64_t rawLinks = 0, rays = 0;
  DetailNodes detail; ///< of the geometry on the GPUs
  /// What the detail kernels read on partition `d` under these options.
  DetailParams detailParams(const EngineDevice& d, bool twoSided) const;
};
}
