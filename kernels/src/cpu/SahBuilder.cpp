// A binned surface-area-heuristic build into the GPU's node layout, on the CPU: the
// alternative to the GPU's linear BVH (slower to build, tighter to trace). One triangle per
// leaf, as the layout requires; the boxes come from the same bottom-up pass as a refit.
#include "shared/BvhBuild.h"

#include <algorithm>
#include <array>

namespace linkgi
{
namespace
{
constexpr int kBins = 32;

float area(const bvh::Box& b)
{
  const Vec3f d = b.hi - b.lo;
  return d.x < 0.f ? 0.f : 2.f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

struct Split
{
  int axis = -1, bin = 0;
  float cost = 3.4e38f;
};

/// The best bin boundary over all three axes for triangles ids[begin, end).
Split bestSplit(const std::vector<Index>& ids, std::size_t begin, std::size_t end,
  const std::vector<bvh::Box>& boxes, const std::vector<Vec3f>& centroids, const bvh::Box& bounds)
{
  Split best;
  for (int axis = 0; axis < 3; ++axis)
  {
    const float lo = bounds.lo[axis], extent = bounds.hi[axis] - lo;
    if (!(extent > 0.f))
    {
      continue;
    }
    std::array<bvh::Box, kBins> binBox;
    std::array<std::size_t, kBins> binCount{};
    for (std::size_t i = begin; i < end; ++i)
    {
      const int b = std::min(kBins - 1, int((centroids[ids[i]][axis] - lo) / extent * kBins));
      binBox[b].grow(boxes[ids[i]]);
      ++binCount[b];
    }
    std::array<float, kBins> rightCost{};
    bvh::Box right;
    std::size_t rightCount = 0;
    for (int b = kBins - 1; b > 0; --b)
    {
      right.grow(binBox[b]);
      rightCount += binCount[b];
      rightCost[b] = area(right) * float(rightCount);
    }
    bvh::Box left;
    std::size_t leftCount = 0;
    for (int b = 1; b < kBins; ++b)
    {
      left.grow(binBox[b - 1]);
      leftCount += binCount[b - 1];
      const float cost = area(left) * float(leftCount) + rightCost[b];
      if (leftCount > 0 && leftCount < end - begin && cost < best.cost)
      {
        best = { axis, b, cost };
      }
    }
  }
  return best;
}
}

void HostBvh::buildSah(const std::vector<Vec3f>& positions, const std::vector<Triangle>& tris)
{
  const std::size_t n = tris.size();
  nodes.assign(n > 1 ? n - 1 : 1, BvhNode{});
  leafParents.assign(n, -1);
  triangles.resize(n);
  std::vector<bvh::Box> boxes(n);
  std::vector<Vec3f> centroids(n);
  std::vector<Index> ids(n);
  for (std::size_t t = 0; t < n; ++t)
  {
    for (Index v : tris[t].v)
    {
      boxes[t].grow(positions[v]);
    }
    centroids[t] = (boxes[t].lo + boxes[t].hi) * 0.5f;
    ids[t] = Index(t);
  }
  // Ranges still to split: (begin, end, node to fill). Leaf positions are range starts.
  struct Range
  {
    std::size_t begin, end;
    int node;
  };
  std::vector<Range> todo;
  int next = 0;
  if (n > 1)
  {
    todo.push_back({ 0, n, next++ });
    nodes[0].parent = -1;
  }
  while (!todo.empty())
  {
    const Range r = todo.back();
    todo.pop_back();
    bvh::Box bounds;
    for (std::size_t i = r.begin; i < r.end; ++i)
    {
      bounds.grow(centroids[ids[i]]);
    }
    const Split s = bestSplit(ids, r.begin, r.end, boxes, centroids, bounds);
    std::size_t mid = r.begin + (r.end - r.begin) / 2; // coincident centroids: halve
    if (s.axis >= 0)
    {
      const float lo = bounds.lo[s.axis], extent = bounds.hi[s.axis] - lo;
      mid = std::partition(ids.begin() + r.begin, ids.begin() + r.end, [&](Index t) {
        return std::min(kBins - 1, int((centroids[t][s.axis] - lo) / extent * kBins)) < s.bin;
      }) - ids.begin();
    }
    const std::size_t halves[2][2] = { { r.begin, mid }, { mid, r.end } };
    for (int c = 0; c < 2; ++c)
    {
      const auto [begin, end] = halves[c];
      if (end - begin == 1)
      {
        nodes[r.node].child[c] = ~int(begin);
        leafParents[begin] = r.node;
        continue;
      }
      const int child = next++;
      nodes[r.node].child[c] = child;
      nodes[child].parent = r.node;
      todo.push_back({ begin, end, child });
    }
  }
  for (std::size_t p = 0; p < n; ++p)
  {
    triangles[p].id = ids[p];
  }
  refit(positions, tris);
}
}
