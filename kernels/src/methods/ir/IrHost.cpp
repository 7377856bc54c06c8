#include "methods/ir/IrHost.h"

#include "linkgi/Error.h"
#include "cpu/Parallel.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_map>

namespace linkgi::ir
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
      const float cone = 2.f * kPi * (1.f - std::cos(l.coneAngleDegrees * (kPi / 180.f)));
      const float extent = l.type == LightType::Directional ? kPi * radius * radius
        : l.type == LightType::Spot                          ? cone
                                                             : 4.f * kPi;
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
  v.centre = (lo + hi) * 0.5f;
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

ProxyGrid proxyGrid(const SceneExtent& extent, std::uint32_t resolution)
{
  ProxyGrid grid;
  grid.lo = extent.lo;
  const Vec3f size = extent.hi - extent.lo;
  grid.cell = std::max(std::max(size.x, size.y), std::max(size.z, 1e-30f)) / float(resolution);
  grid.resolution = resolution;
  return grid;
}

Proxy buildProxy(const Scene& s, std::uint32_t resolution)
{
  Proxy proxy;
  SceneExtent extent;
  positionBounds(s.positions, extent.lo, extent.hi);
  const ProxyGrid grid = proxyGrid(extent, resolution);
  std::unordered_map<std::uint64_t, Index> clusterOf;
  std::vector<Index> vertexCluster(s.vertexCount());
  std::vector<float> members;
  for (std::size_t v = 0; v < s.vertexCount(); ++v)
  {
    const auto inserted = clusterOf.emplace(grid.cellOf(s.positions[v]), Index(proxy.positions.size()));
    if (inserted.second)
    {
      proxy.positions.push_back(Vec3f(0.f));
      members.push_back(0.f);
    }
    const Index k = inserted.first->second;
    vertexCluster[v] = k;
    proxy.positions[k] += s.positions[v];
    members[k] += 1.f;
  }
  for (std::size_t k = 0; k < proxy.positions.size(); ++k)
  {
    proxy.positions[k] = proxy.positions[k] / members[k];
  }
  for (const Triangle& t : s.triangles)
  {
    const Triangle p{ { vertexCluster[t.v[0]], vertexCluster[t.v[1]], vertexCluster[t.v[2]] } };
    if (p.v[0] != p.v[1] && p.v[1] != p.v[2] && p.v[0] != p.v[2])
    {
      proxy.triangles.push_back(p);
    }
  }
  // Many fine triangles collapse onto one coarse one: keep each once.
  const auto key = [](const Triangle& t) {
    Index a = t.v[0], b = t.v[1], c = t.v[2];
    if (a > b) std::swap(a, b);
    if (b > c) std::swap(b, c);
    if (a > b) std::swap(a, b);
    return std::make_tuple(a, b, c);
  };
  std::sort(proxy.triangles.begin(), proxy.triangles.end(),
    [&](const Triangle& x, const Triangle& y) { return key(x) < key(y); });
  proxy.triangles.erase(std::unique(proxy.triangles.begin(), proxy.triangles.end(),
                          [&](const Triangle& x, const Triangle& y) { return key(x) == key(y); }),
    proxy.triangles.end());
  proxy.margin = grid.margin();
  return proxy;
}
}
