// The implicit-visibility method (Dong, Kautz, Theobalt & Seidel 2007): its stages and what
// makes each stale. Formulas in ClusterTree.h and ImplicitLinks.h; the CPU backend in
// IvCpu.cpp, the CUDA backend in IvCuda.cpp. Documentation/Methods.md, "Implicit visibility".
#include "methods/iv/IvBackends.h"
#include "shared/DetailNodes.h"
#include "engine/Progression.h"

#include "cpu/CpuGeometry.h"

#include "cpu/Parallel.h"

namespace linkgi
{
bool operator==(const ImplicitVisibilityOptions& a, const ImplicitVisibilityOptions& b)
{
  return a.binsPerSide == b.binsPerSide;
}
}

namespace linkgi::iv
{
namespace
{
using namespace engine;

/// Node links that the link stage holds at its peak (each task's links after keeping
/// each receiver's shortest per bin, and their CSR), per vertex and bin per side, where
/// nothing was sampled yet (what a refusal before the sample advises): calibrated on the
/// peaks of rooms from 8.6k to 121k vertices. The count depends on how much of the scene
/// each part sees, not on sizes alone: the CPU backend's sample found 11 on the torso, 30
/// on colorlamp, 36 on cornell, 60 on iphi and 69 on tearoom (Documentation/Methods.md,
/// "Memory").
constexpr double kKeptLinks = 42.0;

/// What each worker's allocator arena keeps of the links its tasks created and freed,
/// whatever the scene: on 16 threads small scenes peak 10-17 MiB above 2 threads' (colorlamp,
/// the torso), more than their links grow.
constexpr std::uint64_t kWorkerBytes = std::uint64_t(1) << 19;

/// Bytes of a node: 3 indices, 2 vectors and 4 floats.
constexpr std::uint64_t kNodeBytes = 3 * sizeof(Index) + 2 * sizeof(Vec3f) + 4 * sizeof(float);

/// Host bytes of an update: the geometry and the cluster tree (two nodes per vertex); at
/// the link stage its links (linkStageBytesPerVertex): sampled on the CPU, elsewhere at
/// kKeptLinks node links and a leaf's hemisphere of bins; per element the vectors of the
/// bounces. Not a bound where nothing was sampled: the node links depend on the scene. On
/// the GPU the links are the device's: the host builds the tree and uploads its node
/// records. The device's memory is not estimated (the pair recursion holds every link it
/// creates before each bin keeps its shortest: 90-140 KB per vertex at N = 12 on an H200);
/// the backend falls back to the CPU when a GPU runs out.
MemoryEstimate estimateIvMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t stale, bool cuda)
{
  const std::uint64_t v = shape.vertices, n = o.implicitVisibility.binsPerSide;
  MemoryEstimate m;
  m.hostBytes = cpuSolutionBytes(shape, o) + 2 * v * kNodeBytes;
  if (!cuda && (stale & (1u << kElementStage)))
  {
    m.hostBytes += cpuGeometryBytes(shape);
  }
  {
    // The detail nodes at their bound: the grids, each node, and on the CPU its E_d staged
    // and kept and its radiance in the bounces (on the GPU those are the device's).
    const std::uint64_t nodes = detailNodeBound(shape.vertices, shape.triangles);
    m.hostBytes += shape.triangles * (sizeof(Index) + sizeof(std::uint16_t)) +
      nodes * (sizeof(DetailNode) + (cuda ? 0 : 3 * sizeof(Vec3f)));
  }
  if (stale & (1u << kLinkStage))
  {
    if (cuda)
    {
      m.hostBytes += 2 * v * kNodeBytes;
    }
    else
    {
      const LinkCounts unsampled{ kKeptLinks * double(n), kKeptLinks * double(n), double(3 * n * n + 6 * n) };
      const double perVertex = shape.sampledPerElement > 0.0 ? shape.sampledPerElement : linkStageBytesPerVertex(unsampled);
      m.hostBytes += std::uint64_t(perVertex * double(v)) + std::uint64_t(workerCount()) * kWorkerBytes;
    }
  }
  return m;
}

class ImplicitVisibilityMethod final : public MethodSpec
{
public:
  const char* name() const override { return "implicit-visibility"; }
  const std::vector<StageSpec>& stages() const override
  {
    // The links are rebuilt whenever the geometry moves: that is the method (no rays, so
    // a new structure per frame is affordable). kSampling holds the partition's rows under
    // MPI (which leaves a process pushes to); the method reads none of its rays, twist and
    // seed. Shares: torso on the CPU at N = 12.
    static const std::vector<StageSpec> table = {
      { "Elements", "ElementUpdates", kGeometry, 0u, 5.0 },
      { "ImplicitLinks", "ImplicitLinkBuilds", kMethodOptions | kEnvironmentLayout | kSampling, 1u << kElementStage, 80.0 },
      { "LightLinks", "LightLinkBuilds", kLights | kLightSampling | kSides, 1u << kElementStage, 10.0 },
      { "Bounces", "BounceRuns", kEverything, (1u << kElementStage) | (1u << kLinkStage) | (1u << kLightLinkStage), 5.0 },
    };
    return table;
  }
  void validateOptions(const SolverOptions& o) const override
  {
    if (o.implicitVisibility.binsPerSide < 2 || o.implicitVisibility.binsPerSide > 32)
    {
      throw Error("Implicit visibility: the bins per side of a cube-map face must be between 2 "
                  "and 32 (the paper uses 8, 12, 16); got " +
        std::to_string(o.implicitVisibility.binsPerSide) + ".");
    }
  }
  void checkCombination(const SolverOptions& o) const override
  {
    if (o.twoSided)
    {
      throw Error("The implicit-visibility method has one-sided elements only; turn two-sided "
                  "elements off or choose another method.");
    }
  }
  bool optionsDiffer(const SolverOptions& a, const SolverOptions& b) const override
  {
    return a.implicitVisibility != b.implicitVisibility;
  }
  std::string sampling(const SolverOptions& o) const override
  {
    return std::to_string(o.implicitVisibility.binsPerSide) + " bins per side";
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions& o) const override { return createCpuBackend(o); }
#if LINKGI_HAVE_CUDA
  std::unique_ptr<MethodBackend> createCuda(const SolverOptions& o) const override { return createCudaBackend(o); }
  bool hasCudaBackend() const override { return true; }
#endif
  double sampleWork(std::size_t elements, const SolverOptions& o) const override
  {
    // Links per element are bounded by the bins of its cube map.
    const double n = o.implicitVisibility.binsPerSide;
    return double(elements) * 6.0 * n * n;
  }
  SolverOptions coarser(const SolverOptions& o, double fraction) const override
  {
    SolverOptions c = o;
    c.implicitVisibility.binsPerSide = std::max(2u, std::min(o.implicitVisibility.binsPerSide,
      static_cast<std::uint32_t>(o.implicitVisibility.binsPerSide * std::sqrt(fraction))));
    return c;
  }
  MemoryEstimate estimateMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t stale,
    bool cuda) const override
  {
    return estimateIvMemory(shape, o, stale, cuda);
  }
  // The node links depend on how much of the scene each part sees, more than on its size:
  // the CPU backend links a sample of the leaves first (IvCpu::sampleMemory).
  int memorySampleStage() const override { return kLinkStage; }
};
}

double linkStageBytesPerVertex(const LinkCounts& l)
{
  // Each worker's tasks hold links not yet reduced, and its allocator arena keeps what
  // they free: tearoom peaks 1.6x higher on 16 cores than on 2 (Methods.md, "Memory").
  const double created = l.created * (1.0 + workerCount() / 32.0);
  return created * double(sizeof(std::pair<Index, Index>) + sizeof(Index)) +
    l.leafEntries * double(sizeof(Index) + sizeof(float)) + 2.0 * 2.0 * double(kNodeBytes);
}

const MethodSpec& implicitVisibilityMethod()
{
  static const ImplicitVisibilityMethod method;
  return method;
}
}
