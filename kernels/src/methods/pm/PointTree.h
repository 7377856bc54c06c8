// A static kd-tree over points, for photon mapping's neighbour searches (photons, radiance
// estimate sites, cluster centres): k nearest, or the nearest, that pass a predicate.
#pragma once

#include "methods/pm/PmTypes.h"

#include "linkgi/Math.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace linkgi::pm
{
class PointTree
{
public:
  PointTree() = default;
  /// Indexes `points`. The tree keeps their data pointer: the array must outlive it and not
  /// reallocate (moving or swapping the vector is fine).
  explicit PointTree(const std::vector<Vec3f>& points);

  /// Up to k of the points nearest to `q` for which accept(index) holds, within
  /// sqrt(maxDistance2), into `found` (the caller's, one per thread), nearest first; kNearest
  /// on view(). Returns how many.
  template <typename Accept>
  std::size_t nearest(const Vec3f& q, std::uint32_t k, float maxDistance2, Accept&& accept,
    std::vector<Neighbour>& found) const
  {
    found.resize(k);
    found.resize(kNearest(view(), q, k, maxDistance2, accept, found.data()));
    std::sort(found.begin(), found.end(), nearer);
    return found.size();
  }

  std::size_t size() const { return order.size(); }
  /// The tree as plain arrays (PmTypes.h), valid while this tree and its points live.
  PointTreeView view() const { return { points, order.data(), axes.data(), std::uint32_t(order.size()) }; }

private:
  void build(std::size_t begin, std::size_t end);

  const Vec3f* points = nullptr;
  std::vector<Index> order;            ///< the points, in the implicit tree's order
  std::vector<std::uint8_t> axes;      ///< split axis of the node whose median is order[i]
};
}
