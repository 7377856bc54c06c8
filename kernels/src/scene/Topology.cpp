#include "scene/Topology.h"

#include "cpu/Parallel.h"

#include <algorithm>
#include <numeric>

namespace linkgi
{
// A counting sort: linear, no global sort.
void incidentTriangles(std::size_t vertexCount, const std::vector<Triangle>& triangles,
  std::vector<Index>& offsets, std::vector<Index>& incident)
{
  offsets.assign(vertexCount + 1, 0);
  for (const Triangle& t : triangles)
  {
    for (Index v : t.v)
    {
      ++offsets[v + 1];
    }
  }
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  incident.resize(offsets[vertexCount]);
  std::vector<Index> fill(offsets.begin(), offsets.end() - 1);
  for (Index t = 0; t < triangles.size(); ++t)
  {
    for (Index v : triangles[t].v)
    {
      incident[fill[v]++] = t;
    }
  }
}

// Each one-ring is gathered from the vertex's triangles and sorted on its own, in parallel.
// Edges (a < b) come out in (a, b) order: vertex a's neighbours above a, in ring order.
Topology Topology::build(std::size_t vertexCount, const std::vector<Triangle>& triangles)
{
  Topology topo;
  std::vector<Index> triOffsets, incident;
  incidentTriangles(vertexCount, triangles, triOffsets, incident);

  // Ring sizes first (gathered twice: cheaper than storing every ring separately).
  const auto gatherRing = [&](std::size_t v, std::vector<Index>& ring) {
    ring.clear();
    for (Index i = triOffsets[v]; i < triOffsets[v + 1]; ++i)
    {
      for (Index u : triangles[incident[i]].v)
      {
        if (u != v)
        {
          ring.push_back(u);
        }
      }
    }
    std::sort(ring.begin(), ring.end());
    ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  };
  std::vector<Index> ringSize(vertexCount), above(vertexCount);
  parallelRanges(vertexCount, 2048, [&](std::size_t begin, std::size_t end) {
    std::vector<Index> ring;
    for (std::size_t v = begin; v < end; ++v)
    {
      gatherRing(v, ring);
      ringSize[v] = Index(ring.size());
      above[v] = Index(ring.end() - std::upper_bound(ring.begin(), ring.end(), Index(v)));
    }
  });
  topo.neighbourOffsets.assign(vertexCount + 1, 0);
  std::partial_sum(ringSize.begin(), ringSize.end(), topo.neighbourOffsets.begin() + 1);
  std::vector<Index> edgeBase(vertexCount + 1, 0);
  std::partial_sum(above.begin(), above.end(), edgeBase.begin() + 1);
  topo.neighbours.resize(topo.neighbourOffsets[vertexCount]);
  topo.vertexEdges.resize(topo.neighbours.size());
  topo.edges.resize(edgeBase[vertexCount]);
  parallelRanges(vertexCount, 2048, [&](std::size_t begin, std::size_t end) {
    std::vector<Index> ring;
    for (std::size_t v = begin; v < end; ++v)
    {
      gatherRing(v, ring);
      std::copy(ring.begin(), ring.end(), topo.neighbours.begin() + topo.neighbourOffsets[v]);
      const Index firstAbove = Index(ring.size()) - above[v];
      for (Index j = firstAbove; j < ring.size(); ++j)
      {
        topo.edges[edgeBase[v] + j - firstAbove] = { Index(v), ring[j] };
      }
    }
  });
  // The edge of (v, u) is u's when u < v: found in u's sorted ring.
  parallelRanges(vertexCount, 2048, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      const Index first = topo.neighbourOffsets[v], count = ringSize[v];
      const Index firstAbove = count - above[v];
      for (Index j = 0; j < count; ++j)
      {
        const Index u = topo.neighbours[first + j];
        if (u > v)
        {
          topo.vertexEdges[first + j] = edgeBase[v] + j - firstAbove;
          continue;
        }
        const auto ringU = topo.neighbours.begin() + topo.neighbourOffsets[u];
        const auto aboveU = ringU + (ringSize[u] - above[u]);
        const auto at = std::lower_bound(aboveU, ringU + ringSize[u], Index(v));
        topo.vertexEdges[first + j] = edgeBase[u] + Index(at - aboveU);
      }
    }
  });
  return topo;
}
}
