#include "linkgi/Topology.h"

#include <algorithm>
#include <numeric>

namespace linkgi
{
Topology Topology::build(std::size_t vertexCount, const std::vector<Triangle>& triangles)
{
  Topology topo;
  std::vector<std::uint64_t> keys;
  keys.reserve(triangles.size() * 3);
  for (const Triangle& t : triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const Index a = t.v[k], b = t.v[(k + 1) % 3];
      keys.push_back((std::uint64_t(std::min(a, b)) << 32) | std::max(a, b));
    }
  }
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  topo.edges.resize(keys.size());
  for (std::size_t e = 0; e < keys.size(); ++e)
  {
    topo.edges[e] = { Index(keys[e] >> 32), Index(keys[e] & 0xffffffffu) };
  }

  topo.neighbourOffsets.assign(vertexCount + 1, 0);
  for (const auto& [a, b] : topo.edges)
  {
    ++topo.neighbourOffsets[a + 1];
    ++topo.neighbourOffsets[b + 1];
  }
  std::partial_sum(
    topo.neighbourOffsets.begin(), topo.neighbourOffsets.end(), topo.neighbourOffsets.begin());
  topo.neighbours.resize(topo.edges.size() * 2);
  topo.vertexEdges.resize(topo.edges.size() * 2);
  std::vector<Index> fill(topo.neighbourOffsets.begin(), topo.neighbourOffsets.end() - 1);
  for (Index e = 0; e < topo.edges.size(); ++e)
  {
    const auto [a, b] = topo.edges[e];
    topo.neighbours[fill[a]] = b;
    topo.vertexEdges[fill[a]++] = e;
    topo.neighbours[fill[b]] = a;
    topo.vertexEdges[fill[b]++] = e;
  }
  // Sort each one-ring by neighbour index, keeping the edge indices alongside.
  std::vector<std::pair<Index, Index>> ring;
  for (std::size_t v = 0; v < vertexCount; ++v)
  {
    const Index begin = topo.neighbourOffsets[v], end = topo.neighbourOffsets[v + 1];
    ring.clear();
    for (Index i = begin; i < end; ++i)
    {
      ring.emplace_back(topo.neighbours[i], topo.vertexEdges[i]);
    }
    std::sort(ring.begin(), ring.end());
    for (Index i = begin; i < end; ++i)
    {
      topo.neighbours[i] = ring[i - begin].first;
      topo.vertexEdges[i] = ring[i - begin].second;
    }
  }
  return topo;
}
}
