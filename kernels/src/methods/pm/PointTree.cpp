#include "methods/pm/PointTree.h"

#include <numeric>

namespace linkgi::pm
{
PointTree::PointTree(const std::vector<Vec3f>& p) : points(p.data()), order(p.size()), axes(p.size(), 0)
{
  std::iota(order.begin(), order.end(), Index(0));
  build(0, order.size());
}

void PointTree::build(std::size_t begin, std::size_t end)
{
  if (end - begin <= kTreeLeaf)
  {
    return;
  }
  Vec3f lo = points[order[begin]], hi = lo;
  for (std::size_t i = begin; i < end; ++i)
  {
    const Vec3f& q = points[order[i]];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = std::min(lo[a], q[a]);
      hi[a] = std::max(hi[a], q[a]);
    }
  }
  const Vec3f extent = hi - lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  const std::size_t mid = (begin + end) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
    [&](Index a, Index b) { return points[a][axis] < points[b][axis]; });
  axes[mid] = std::uint8_t(axis);
  build(begin, mid);
  build(mid + 1, end);
}
}
