// The link-structure method (Schmitz, Tavenrath & Kobbelt 2008): its stages and what makes
// each stale. The formulas live in Links.h, DirectLight.h and Bounce.h; the backends in
// LinksCpu.cpp and cuda/LinksCuda.cpp.
#include "methods/links/LinksBackends.h"
#include "engine/Progression.h"

namespace linkgi::links
{
namespace
{
using namespace engine;

class LinksMethod final : public MethodSpec
{
public:
  const char* name() const override { return "links"; }
  const std::vector<StageSpec>& stages() const override
  {
    // Progress shares: a full update of conference on the CPU spends ~85% in the links.
    static const std::vector<StageSpec> table = {
      { "Geometry", "", kGeometry | kBackendSetup, 0u, 5.0 },
      { "Links", "LinkBuilds", kSampling | kSides | kEnvironmentLayout, 1u << kGeometryStage, 80.0 },
      { "LightLinks", "LightLinkBuilds", kLights | kLightSampling | kSides, 1u << kGeometryStage, 10.0 },
      { "Bounces", "BounceRuns", kEverything, (1u << kGeometryStage) | (1u << kLinkStage) | (1u << kLightLinkStage), 5.0 },
    };
    return table;
  }
  std::string sampling(const SolverOptions& o) const override
  {
    return std::to_string(o.raysPerVertex) + " rays";
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions& o) const override { return createCpuBackend(o); }
#if LINKGI_HAVE_CUDA
  std::unique_ptr<MethodBackend> createCuda(const SolverOptions& o) const override { return createCudaBackend(o); }
  bool hasCudaBackend() const override { return true; }
#endif
  double sampleWork(std::size_t elements, const SolverOptions& o) const override
  {
    return double(elements) * o.raysPerVertex; // the link rays
  }
  SolverOptions coarser(const SolverOptions& o, double fraction) const override
  {
    SolverOptions c = o;
    // 3x3 directions at least: with 2x2 the fixed elevations of the strata bias the mean
    // (conference's indirect light 25% high on an H200, 4% at 3x3, against 256 rays).
    c.raysPerVertex = scaledSquare(o.raysPerVertex, fraction, 9);
    return c;
  }
  // The links a row keeps depend on how many rays hit and how many hit the same vertices,
  // which the sizes do not tell: 0.2-0.8 of their bound in rooms, a fifth on a model in no
  // room. The CPU backend links a sample of rows first (LinksCpu::sampleMemory).
  int memorySampleStage() const override { return kLinkStage; }
  MemoryEstimate estimateMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t stale,
    bool cuda) const override
  {
    if (!cuda)
    {
      return estimateCpuMemory(shape, o, stale);
    }
    // The CUDA engine keeps the matrix on the GPUs and sizes its link batches to their free
    // memory (cuda/CudaLinks.cpp), so the host holds per-element arrays only: the staged
    // uploads and downloads and the solution (~16 3-vectors). The device figure is the
    // matrix at its bound plus the BVH and per-element vectors; the CUDA backend itself
    // falls back to the CPU when a GPU runs out.
    const std::uint64_t e = shape.vertices * (o.twoSided ? 2 : 1);
    MemoryEstimate m;
    const std::uint64_t nodes = detailColumnBound(shape, o);
    m.hostBytes = e * sizeof(Vec3f) * 16 + nodes * sizeof(DetailNode);
    if (stale & (1u << kLinkStage))
    {
      const LinksPerElement links = linksPerElement(shape, o);
      m.deviceBytes += e * (links.transport + links.environment) * (sizeof(Index) + sizeof(float));
    }
    m.deviceBytes += shape.triangles * 128 + e * 16 * 12 + nodes * (sizeof(DetailNode) + 3 * 16);
    return m;
  }
};
}

const MethodSpec& linksMethod()
{
  static const LinksMethod method;
  return method;
}
}
