// Instant radiosity on the CPU: Embree (or our BVH) through the RayTracer interface, loops
// on the engine's thread pool; the direct light is the shared light-link stage.
#include "methods/ir/IrBackends.h"

#include "cpu/CpuGeometry.h"
#include "engine/MemoryBudget.h"

#include "shared/Bounce.h"
#include "linkgi/Memory.h"
#include "shared/DirectLight.h"

#include <atomic>
#include <chrono>
#include <cmath>

namespace linkgi::ir
{
std::vector<Vec3f> gatherCpu(const Scene& s, const std::vector<RayOrigin>& origins, const VplSet& set,
  const RayTracer* visibility, const GatherParams& gp, bool twoSided, std::uint64_t* rays,
  const ProgressCallback& progress, const std::uint8_t* rows)
{
  const Elements elements{ s.vertexCount(), twoSided };
  std::vector<Vec3f> irradiance(elements.count());
  std::atomic<std::uint64_t> traced{ 0 };
  const std::uint32_t subsets = std::uint32_t(set.subsetScale.size());
  parallelFor("Gather", elements.count(), 16, [&](std::size_t first, std::size_t last) {
    std::vector<Ray> batch;
    std::vector<Vec3f> contribution;
    std::vector<std::uint8_t> blocked;
    std::uint64_t count = 0;
    for (std::size_t e = first; e < last; ++e)
    {
      if (rows && !rows[e])
      {
        continue; // another process's row
      }
      const Index v = elements.vertexOf(e);
      const float sign = elements.sideSign(e);
      const Vec3f n = s.normals[v] * sign;
      const Vec3f x = s.positions[v] + origins[v].shift;
      const Vec3f origin = vertexLightOrigin(s.positions[v], s.normals[v], origins[v], sign);
      const std::uint32_t r = vertexSubset(v, subsets, gp.seed);
      batch.clear();
      contribution.clear();
      for (std::uint32_t k = set.subsetOffsets[r]; k < set.subsetOffsets[r + 1]; ++k)
      {
        Ray ray;
        const Vec3f e_k = vplIrradiance(set.vpls[k], x, origin, n, gp.dmin, ray);
        if (maxComponent(e_k) > 0.f && (gp.proxyMargin <= 0.f || proxyShadowRay(ray, gp.proxyMargin)))
        {
          batch.push_back(ray);
          contribution.push_back(e_k);
        }
        else if (maxComponent(e_k) > 0.f)
        {
          irradiance[e] += e_k; // too close for the proxy to tell: visible
        }
      }
      blocked.assign(batch.size(), 0);
      if (visibility && !batch.empty())
      {
        visibility->occluded(batch.data(), blocked.data(), batch.size());
      }
      count += batch.size();
      Vec3f sum = irradiance[e];
      for (std::size_t i = 0; i < batch.size(); ++i)
      {
        if (!blocked[i])
        {
          sum += contribution[i];
        }
      }
      irradiance[e] = sum * set.subsetScale[r];
    }
    traced += count;
  }, progress);
  if (rays)
  {
    *rays = traced;
  }
  return irradiance;
}

std::vector<Vec3f> compensateCpu(const Scene& s, const std::vector<RayOrigin>& origins,
  const RayTracer& tracer, const CompensationInputs& inputs, const std::vector<Vec3f>& indirect,
  std::uint32_t rays, std::uint32_t seed)
{
  const Elements elements{ s.vertexCount(), inputs.twoSided };
  const std::uint32_t k = squareSide(rays);
  std::vector<Vec3f> out(indirect);
  parallelFor("Compensation", elements.count(), 64, [&](std::size_t first, std::size_t last) {
    std::vector<Ray> batch(rays);
    std::vector<Hit> hits(rays);
    const auto indirectAt = [&indirect](Index e) { return indirect[e]; };
    const ClosestHit trace{ tracer };
    const AnyHit occluded{ tracer };
    for (std::size_t e = first; e < last; ++e)
    {
      const Index v = elements.vertexOf(e);
      const Vec3f n = s.normals[v] * elements.sideSign(e);
      const Frame frame = vertexFrame(n, true, seed, Index(e));
      const Vec3f origin = elementRayOrigin(s.positions[v], n, origins[v]);
      const std::uint32_t key = compensationKey(seed, Index(e));
      for (std::uint32_t i = 0; i < rays; ++i)
      {
        batch[i] = compensationRay(origin, frame, i, k, inputs.dmin, key);
      }
      tracer.trace(batch.data(), hits.data(), rays);
      Vec3f sum(0.f);
      for (std::uint32_t i = 0; i < rays; ++i)
      {
        sum += compensationSample(inputs, batch[i], hits[i], indirectAt, trace, occluded);
      }
      out[e] += sum * (kPi / float(rays));
    }
  }, {});
  return out;
}

namespace
{
using namespace engine;

class IrCpu final : public MethodBackend
{
public:
  void run(std::size_t stage, const StageContext& c) override
  {
    switch (stage)
    {
      case kGeometryStage:
        geometryTouched = true;
        return geometry.update(c);
      case kProxyStage:
        return buildProxyTracer(c);
      case kVplStage:
        return traceVpls(c);
      case kLightLinkStage:
        direct.stage() = computeDirectLight(c.scene, geometry.topology, geometry.origins,
          *geometry.tracer, c.options.twoSided, c.options.lightOversampling, c.progress);
        return;
      case kGatherStage:
        return gather(c);
      case kFinishStage:
        return finish(c);
    }
  }

  void commit() override
  {
    vpls.commit();
    direct.commit();
    gathered.commit();
    geometryTouched = false;
  }

  bool discard() override
  {
    vpls.discard();
    direct.discard();
    gathered.discard();
    // The tracers and host geometry are updated in place (see LinksCpu).
    const bool whole = !geometryTouched;
    geometryTouched = false;
    return whole;
  }

  void describe(SolverStats& st) const override
  {
    geometry.describe(st);
    st.rays = gathered.committed().rays;
    st.lightRays = direct.committed().shadowRays;
    st.setCounter("Vpls", vpls.committed().count());
  }

  const RayTracer* sceneTracer() const override { return geometry.tracer.get(); }

private:
  void buildProxyTracer(const StageContext& c)
  {
    geometryTouched = true;
    proxyTracer.reset();
    proxyMargin = 0.f;
    const InstantRadiosityOptions& o = c.options.instantRadiosity;
    if (!o.proxyVisibility)
    {
      return;
    }
    proxy = buildProxy(c.scene, o.proxyResolution);
    proxyMargin = proxy.margin;
    if (!proxy.triangles.empty())
    {
      proxyTracer = createCpuRayTracer();
      proxyTracer->build(proxy.positions, proxy.triangles);
    }
  }

  void traceVpls(const StageContext& c)
  {
    const PathSetup setup = buildPathSetup(c.scene, geometry.faceNormals, geometry.origins, c.options);
    const std::uint64_t held = lightPathsHeldBytes(c);
    vpls.stage() = traceVplsCpu(setup, *geometry.tracer, c.options.instantRadiosity.interleave, c.progress,
      memoryLeft(c.stats, held));
    raiseEstimate(c.stats, held + vpls.stage().secondPassBytes);
  }

  void gather(const StageContext& c)
  {
    const VplSet& set = vpls.now();
    GatherParams gp;
    gp.dmin = c.options.instantRadiosity.clampDistance * boundingDiagonal(c.scene.positions);
    gp.proxyMargin = c.options.instantRadiosity.proxyVisibility ? proxyMargin : 0.f;
    gp.seed = c.options.seed;
    const RayTracer* visibility = gp.proxyMargin > 0.f ? proxyTracer.get() : geometry.tracer.get();
    // Under MPI each process gathers its rows; one exchange completes E_ind everywhere, so
    // that the smoothing across partition boundaries sees its neighbours.
    const std::uint8_t* rows = ownRows(c.options, Elements{ c.scene.vertexCount(), c.options.twoSided }.count());
    Gathered& out = gathered.stage();
    out.irradiance = gatherCpu(c.scene, geometry.origins, set, visibility, gp, c.options.twoSided, &out.rays,
      c.progress, rows);
    if (rows)
    {
      c.options.partition->exchange(out.irradiance);
    }
  }

  void finish(const StageContext& c)
  {
    const std::vector<Vec3f>& indirect = gathered.now().irradiance;
    const std::vector<Vec3f>& directLight = direct.now().irradiance;
    const std::uint32_t rays = c.options.instantRadiosity.compensationRays;
    if (rays == 0)
    {
      finishSolution(c, geometry.topology, indirect, directLight);
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    CompensationInputs in;
    in.triangles = c.scene.triangles.data();
    in.positions = c.scene.positions.data();
    in.normals = c.scene.normals.data();
    in.origins = geometry.origins.data();
    in.faceNormals = geometry.faceNormals.data();
    in.albedo = c.scene.albedo.data();
    in.emission = c.scene.emission.empty() ? nullptr : c.scene.emission.data();
    in.direct = directLight.data();
    in.lights = c.scene.lights.data();
    in.lightCount = Index(c.scene.lights.size());
    in.vertexCount = Index(c.scene.vertexCount());
    in.twoSided = c.options.twoSided;
    in.dmin = c.options.instantRadiosity.clampDistance * boundingDiagonal(c.scene.positions);
    std::vector<Vec3f> compensated =
      compensateCpu(c.scene, geometry.origins, *geometry.tracer, in, indirect, rays, c.options.seed);
    c.part("Compensation", msSince(start));
    finishSolution(c, geometry.topology, std::move(compensated), directLight);
  }

  CpuGeometry geometry;
  Proxy proxy;
  std::unique_ptr<RayTracer> proxyTracer;
  float proxyMargin = 0.f;
  bool geometryTouched = false;
  /// The gather stage's results: E_ind per element and the shadow rays it traced.
  struct Gathered
  {
    std::vector<Vec3f> irradiance;
    std::uint64_t rays = 0;
  };
  Staged<VplSet> vpls;
  Staged<DirectLightResult> direct;
  Staged<Gathered> gathered;
};
}

std::unique_ptr<MethodBackend> createCpuBackend(const SolverOptions&)
{
  return std::make_unique<IrCpu>();
}
}
