#include "methods/ir/IrHost.h"

#include "linkgi/Error.h"
#include "cpu/Parallel.h"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <unordered_map>

namespace linkgi::ir
{
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
