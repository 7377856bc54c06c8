// The host-side set-up of light paths (shared/LightPaths.h): sources, path counts, the
// packing of their hits, and the paths traced on the CPU.
#include "shared/LightPaths.h"

#include "linkgi/Error.h"
#include "linkgi/Memory.h"

#include <algorithm>
#include <cmath>

namespace linkgi::paths
{
namespace
{
float mean(const Vec3f& c)
{
  return (c.x + c.y + c.z) * (1.f / 3.f);
}
}

std::uint32_t pathCount(const SolverOptions& o)
{
  const std::uint32_t b = std::max(1u, o.bounces);
  return std::max(1u, (o.instantRadiosity.vplCount + b - 1) / b);
}

std::uint32_t secondPassPaths(std::uint32_t paths, std::size_t found, std::uint32_t target,
  std::uint32_t slotsPerPath)
{
  if (2 * found >= target)
  {
    return 0;
  }
  const double wanted = std::ceil(double(paths) * target / double(std::max<std::size_t>(found, 1)));
  const double cap = std::min(64.0 * paths, double(1u << 22) / slotsPerPath);
  const std::uint32_t more = std::uint32_t(std::min(wanted, cap));
  return more > paths ? more : 0;
}

PathSetup buildPathSetup(const Scene& s, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const SolverOptions& o,
  const SceneExtent* known)
{
  PathSetup setup;
  const SceneExtent extent = known ? *known : sceneExtent(s);
  const Vec3f lo = extent.lo, hi = extent.hi;
  const float radius = std::max(0.5f * length(hi - lo), 1e-30f);
  const Vec3f centre = (lo + hi) * 0.5f;
  std::vector<float> weights;
  const auto add = [&](std::uint32_t kind, Index index, float weight, float area) {
    if (weight > 0.f && std::isfinite(weight))
    {
      setup.sources.push_back({ kind, index, 0.f, area });
      weights.push_back(weight);
    }
  };
  if (o.bounces > 0)
  {
    for (Index i = 0; i < s.lights.size(); ++i)
    {
      const Light& l = s.lights[i];
      const float extent = l.type == LightType::Directional ? kPi * radius * radius
                                                            : emissionCone(l, centre, radius).solidAngle();
      add(kLightSource, i, extent * mean(l.intensity), 0.f);
    }
  }
  // A pass over the vertices first, on all cores (every light move and deformation makes
  // it): a scene's all-black emission array (the usual case) costs no pass over the triangles.
  const std::vector<Vec3f>& emission = s.emission;
  if (firstIndexWhere(emission.size(), 16384, [&](std::size_t i) { return maxComponent(emission[i]) > 0.f; }) <
    emission.size())
  {
    for (Index t = 0; t < s.triangles.size(); ++t)
    {
      const Triangle& tri = s.triangles[t];
      const float le = mean(s.emission[tri.v[0]] + s.emission[tri.v[1]] + s.emission[tri.v[2]]) / 3.f;
      if (!(le > 0.f))
      {
        continue; // no source (add would drop it)
      }
      const Vec3f &a = s.positions[tri.v[0]], &b = s.positions[tri.v[1]], &c = s.positions[tri.v[2]];
      const float area = 0.5f * length(cross(b - a, c - a));
      add(kEmitterSource, t, kPi * area * le, area);
    }
  }
  if (!s.environment.isBlack())
  {
    float texel = 1.f;
    if (s.environment.hasTexture())
    {
      double sum = 0.0;
      for (const Vec3f& t : s.environment.texels)
      {
        sum += mean(t);
      }
      texel = float(sum / double(s.environment.texels.size()));
    }
    add(kEnvironmentSource, 0, 4.f * kPi * kPi * radius * radius * mean(s.environment.color) * texel, 0.f);
  }
  double total = 0.0;
  for (float w : weights)
  {
    total += w;
  }
  double running = 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i)
  {
    setup.sources[i].probability = float(weights[i] / total);
    running += weights[i];
    setup.cdf.push_back(float(running / total));
  }
  PathScene& v = setup.view;
  v.positions = s.positions.data();
  v.normals = s.normals.data();
  v.albedo = s.albedo.data();
  v.emission = s.emission.empty() ? nullptr : s.emission.data();
  v.triangles = s.triangles.data();
  v.faceNormals = faceNormals.data();
  v.lights = s.lights.data();
  v.sources = setup.sources.data();
  v.cdf = setup.cdf.data();
  v.sourceCount = Index(setup.sources.size());
  v.centre = centre;
  v.radius = radius;
  v.envColor = s.environment.color;
  v.envWidth = s.environment.hasTexture() ? s.environment.width : 0;
  v.envHeight = s.environment.hasTexture() ? s.environment.height : 0;
  v.envTexels = s.environment.texels.empty() ? nullptr : s.environment.texels.data();
  v.paths = pathCount(o);
  v.bounces = o.bounces;
  v.twoSided = o.twoSided;
  v.russianRoulette = o.instantRadiosity.russianRoulette;
  v.seed = o.seed;
  v.origins = origins.empty() ? nullptr : origins.data();
  setup.dmin = o.instantRadiosity.clampDistance * extent.diagonal;
  setup.targetVpls = o.instantRadiosity.vplCount;
  return setup;
}

VplSet packVpls(const std::vector<Vpl>& slots, const std::vector<int>& counts,
  std::uint32_t slotsPerPath, std::uint32_t subsets)
{
  VplSet set;
  const std::uint32_t paths = std::uint32_t(counts.size());
  subsets = std::max(1u, std::min(subsets, paths));
  set.subsetOffsets.push_back(0);
  for (std::uint32_t r = 0; r < subsets; ++r)
  {
    const std::uint32_t first = subsetFirstPath(r, subsets, paths), last = subsetFirstPath(r + 1, subsets, paths);
    for (std::uint32_t p = first; p < last; ++p)
    {
      const Vpl* begin = slots.data() + std::size_t(p) * slotsPerPath;
      set.vpls.insert(set.vpls.end(), begin, begin + counts[p]);
    }
    set.subsetOffsets.push_back(std::uint32_t(set.vpls.size()));
    set.subsetScale.push_back(float(paths) / float(last - first));
  }
  return set;
}

VplSet traceVplsCpu(const PathSetup& setup, const RayTracer& tracer, std::uint32_t subsets,
  const ProgressCallback& progress, std::uint64_t secondPassBytes)
{
  PathScene view = setup.view;
  const std::uint32_t slotsPerPath = view.bounces + 1;
  std::vector<Vpl> slots;
  std::vector<int> counts;
  const ClosestHit trace{ tracer };
  const std::uint32_t target = setup.targetVpls;
  std::uint64_t taken = 0;
  for (int pass = 0; pass < 2; ++pass)
  {
    slots.resize(std::size_t(view.paths) * slotsPerPath);
    counts.assign(view.paths, 0);
    parallelFor("VPLs", view.paths, 64, [&](std::size_t first, std::size_t last) {
      for (std::size_t p = first; p < last; ++p)
      {
        counts[p] = traceLightPath(view, std::uint32_t(p), slots.data() + p * slotsPerPath, trace);
      }
    }, progress);
    std::size_t found = 0;
    for (int n : counts)
    {
      found += std::size_t(n);
    }
    const std::uint32_t more = pass == 0 ? secondPassPaths(view.paths, found, target, slotsPerPath) : 0;
    if (!more)
    {
      break;
    }
    // The second pass traces every path anew: the first pass's slots go before its own are
    // allocated.
    const std::uint64_t bytes = std::uint64_t(more) * (slotsPerPath * sizeof(Vpl) + sizeof(int));
    if (bytes > secondPassBytes)
    {
      throw OutOfMemoryBudget("Not enough memory: light paths mostly leave this scene (" + std::to_string(found) +
          " of the " + std::to_string(target) + " virtual lights or photons asked for were found), and the second pass of " +
          std::to_string(more) + " paths that would find the rest needs about " + formatBytes(bytes) +
          ", more than the memory budget leaves (" + formatBytes(secondPassBytes) +
          "). Ask for fewer (NumberOfVPLs, NumberOfPhotons), or a larger MemoryBudget.",
        0);
    }
    std::vector<Vpl>().swap(slots);
    std::vector<int>().swap(counts);
    view.paths = more;
    taken = bytes;
  }
  VplSet set = packVpls(slots, counts, slotsPerPath, subsets);
  set.secondPassBytes = taken;
  return set;
}
}
