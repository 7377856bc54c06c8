// Instant radiosity with virtual point lights (Keller 1997, as Marques & Santos 2010 run it),
// per vertex: nothing is precomputed, so a deformation costs what a light move costs. Its
// stages and what makes each stale; the formulas live in ir/IrMath.h, the backends in
// IrCpu.cpp and IrCuda.cpp.
#include "methods/ir/IrBackends.h"

#include "linkgi/Error.h"
#include "engine/Progression.h"

#include "cpu/CpuGeometry.h"
#include "methods/ir/IrMath.h"

namespace linkgi
{
bool operator==(const InstantRadiosityOptions& a, const InstantRadiosityOptions& b)
{
  return a.vplCount == b.vplCount && a.clampDistance == b.clampDistance &&
    a.interleave == b.interleave && a.proxyVisibility == b.proxyVisibility &&
    a.proxyResolution == b.proxyResolution && a.russianRoulette == b.russianRoulette &&
    a.compensationRays == b.compensationRays;
}
}

namespace linkgi::ir
{
namespace
{
using namespace engine;

/// Host bytes of an update: the geometry, the VPL stage's path slots (one Vpl per bounce
/// and path of the first pass; a second pass, up to 64 times as many paths where most leave
/// the scene, is checked against what the budget leaves beyond the geometry when it is
/// known, and the estimate raised to hold both: lightPathsHeldBytes),
/// the proxy's grid and BVH when visibility uses it, and the per-element vectors. On the GPU
/// the host holds the per-element vectors only.
MemoryEstimate estimateIrMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t stale, bool cuda)
{
  MemoryEstimate m;
  m.hostBytes = cpuSolutionBytes(shape, o);
  if (cuda)
  {
    m.hostBytes += shape.vertices * (o.twoSided ? 2 : 1) * sizeof(Vec3f) * 6;
    return m;
  }
  if (stale & (1u << kGeometryStage))
  {
    m.hostBytes += cpuGeometryBytes(shape);
  }
  if (o.instantRadiosity.proxyVisibility && (stale & (1u << kProxyStage)))
  {
    // The grid's cells, and the proxy's triangles and BVH: at most the mesh's.
    const std::uint64_t r = o.instantRadiosity.proxyResolution + 1;
    m.hostBytes += r * r * r * (sizeof(Vec3f) + sizeof(Index)) + cpuGeometryBytes(shape);
  }
  if (o.instantRadiosity.compensationRays > 0)
  {
    m.hostBytes += shape.vertices * (o.twoSided ? 2 : 1) * sizeof(Vec3f); // E_ind compensated
  }
  if (stale & (1u << kVplStage))
  {
    m.hostBytes += std::uint64_t(pathCount(o)) * (o.bounces + 1) * (sizeof(Vpl) + sizeof(int)) * 2;
  }
  return m;
}

class InstantRadiosityMethod final : public MethodSpec
{
public:
  const char* name() const override { return "instant-radiosity"; }
  const std::vector<StageSpec>& stages() const override
  {
    constexpr std::uint32_t geometry = 1u << kGeometryStage;
    // Every light path is traced again whenever anything it could meet changed: the lights,
    // the materials, the environment, the geometry (through the Geometry stage), the seed,
    // the sides, the bounce count or the method's options. That is the method's point: a
    // deformation costs what a light move costs. Progress shares: the gather is nearly all
    // of an update on either backend.
    static const std::vector<StageSpec> table = {
      { "Geometry", "", kGeometry | kBackendSetup, 0u, 3.0 },
      { "Proxy", "ProxyBuilds", kMethodOptions, geometry, 1.0 },
      { "VPLs", "VplBuilds",
        kLights | kAlbedo | kEmission | kEnvironmentLayout | kEnvironmentRadiance | kSampling |
          kSides | kIteration | kMethodOptions,
        geometry, 3.0 },
      { "LightLinks", "LightLinkBuilds", kLights | kLightSampling | kSides, geometry, 7.0 },
      { "Gather", "GatherRuns", kSides | kMethodOptions,
        geometry | (1u << kProxyStage) | (1u << kVplStage), 80.0 },
      // The clamp's compensation (part "Compensation") reads the direct and the gathered
      // light, so it is here.
      { "Finish", "", kEverything, geometry | (1u << kGatherStage) | (1u << kLightLinkStage), 6.0 },
    };
    return table;
  }
  void validateOptions(const SolverOptions& o) const override
  {
    const InstantRadiosityOptions& ir = o.instantRadiosity;
    if (ir.vplCount < 1 || ir.vplCount > (1u << 20))
    {
      throw Error("The number of virtual point lights must be between 1 and 1048576; got " +
        std::to_string(ir.vplCount) + ".");
    }
    if (!(ir.clampDistance >= 0.f && ir.clampDistance <= 1.f))
    {
      throw Error("The VPL clamp distance must be a fraction of the scene size in [0, 1]; got " +
        std::to_string(ir.clampDistance) + ".");
    }
    if (ir.interleave < 1 || ir.interleave > 64)
    {
      throw Error("The VPL interleaving must be between 1 (off) and 64 subsets; got " +
        std::to_string(ir.interleave) + ".");
    }
    if (ir.compensationRays > 1024 || (ir.compensationRays > 0 && !isPerfectSquare(ir.compensationRays)))
    {
      throw Error("The VPL clamp's compensation rays must be 0 (off) or a perfect square up to 1024; got " +
        std::to_string(ir.compensationRays) + ".");
    }
    if (ir.proxyResolution < 2 || ir.proxyResolution > 4096)
    {
      throw Error("The proxy resolution must be between 2 and 4096 cells; got " +
        std::to_string(ir.proxyResolution) + ".");
    }
  }
  bool optionsDiffer(const SolverOptions& a, const SolverOptions& b) const override
  {
    return a.instantRadiosity != b.instantRadiosity;
  }
  std::string sampling(const SolverOptions& o) const override
  {
    return std::to_string(o.instantRadiosity.vplCount) + " VPLs";
  }
  std::unique_ptr<MethodBackend> createCpu(const SolverOptions& o) const override { return createCpuBackend(o); }
#if LINKGI_HAVE_CUDA
  std::unique_ptr<MethodBackend> createCuda(const SolverOptions& o) const override { return createCudaBackend(o); }
  bool hasCudaBackend() const override { return true; }
#endif
  double sampleWork(std::size_t elements, const SolverOptions& o) const override
  {
    // The gather (each element meets its subset of the VPLs, a shadow ray each) and the
    // clamp's compensation (its rays per element).
    const InstantRadiosityOptions& ir = o.instantRadiosity;
    return double(elements) * (double(ir.vplCount) / ir.interleave + ir.compensationRays);
  }
  SolverOptions coarser(const SolverOptions& o, double fraction) const override
  {
    // At least 4 VPLs in every interleaved subset, and 3x3 compensation rays (2x2 strata
    // bias a mean, as the link method's rays).
    SolverOptions c = o;
    InstantRadiosityOptions& ir = c.instantRadiosity;
    ir.vplCount = scaledCount(ir.vplCount, fraction, std::max(16u, 4 * ir.interleave));
    if (ir.compensationRays > 0)
    {
      ir.compensationRays = scaledSquare(ir.compensationRays, fraction, 9);
    }
    return c;
  }
  MemoryEstimate estimateMemory(const MemoryShape& shape, const SolverOptions& o, std::uint32_t stale,
    bool cuda) const override
  {
    return estimateIrMemory(shape, o, stale, cuda);
  }
};
}

const MethodSpec& instantRadiosityMethod()
{
  static const InstantRadiosityMethod method;
  return method;
}
}
