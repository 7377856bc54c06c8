// A static kd-tree over points, for photon mapping's neighbour searches (photons, radiance
// estimate sites, cluster centres): k nearest, or the nearest, that pass a predicate.
#pragma once

#include "pm/PmTypes.h"

#include "linkgi/Math.h"

#include <algorithm>
#include <cstdint>
#include <utility>
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

  /// Up to k (squared distance, index) pairs of the points nearest to `q` for which
  /// accept(index) holds, within sqrt(maxDistance2), into `found`, nearest first. Returns
  /// how many. `found` is the caller's (one per thread).
  template <typename Accept>
  std::size_t nearest(const Vec3f& q, std::size_t k, float maxDistance2, Accept&& accept,
    std::vector<std::pair<float, Index>>& found) const
  {
    found.clear();
    if (k > 0 && !order.empty())
    {
      search(0, order.size(), q, k, maxDistance2, accept, found);
    }
    std::sort_heap(found.begin(), found.end());
    return found.size();
  }

  std::size_t size() const { return order.size(); }
  /// The tree as plain arrays (PmTypes.h), valid while this tree and its points live.
  PointTreeView view() const { return { points, order.data(), axes.data(), std::uint32_t(order.size()) }; }

private:
  static constexpr std::size_t kLeaf = kTreeLeaf;
  void build(std::size_t begin, std::size_t end);

  template <typename Accept>
  void search(std::size_t begin, std::size_t end, const Vec3f& q, std::size_t k, float& bound,
    Accept& accept, std::vector<std::pair<float, Index>>& heap) const
  {
    const auto consider = [&](Index i) {
      const Vec3f d = points[i] - q;
      const float d2 = dot(d, d);
      if (d2 > bound || !accept(i))
      {
        return;
      }
      heap.emplace_back(d2, i);
      std::push_heap(heap.begin(), heap.end());
      if (heap.size() > k)
      {
        std::pop_heap(heap.begin(), heap.end());
        heap.pop_back();
      }
      if (heap.size() == k)
      {
        bound = heap.front().first;
      }
    };
    if (end - begin <= kLeaf)
    {
      for (std::size_t i = begin; i < end; ++i)
      {
        consider(order[i]);
      }
      return;
    }
    const std::size_t mid = (begin + end) / 2;
    const Index m = order[mid];
    const int axis = axes[mid];
    const float diff = q[axis] - points[m][axis];
    consider(m);
    const bool leftFirst = diff < 0.f;
    search(leftFirst ? begin : mid + 1, leftFirst ? mid : end, q, k, bound, accept, heap);
    if (diff * diff <= bound)
    {
      search(leftFirst ? mid + 1 : begin, leftFirst ? end : mid, q, k, bound, accept, heap);
    }
  }

  const Vec3f* points = nullptr;
  std::vector<Index> order;            ///< the points, in the implicit tree's order
  std::vector<std::uint8_t> axes;      ///< split axis of the node whose median is order[i]
};
}
