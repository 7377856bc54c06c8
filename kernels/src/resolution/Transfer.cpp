// Carrying the proxy's light to the input: the nearest proxy triangle that faces the same
// way, found in a uniform grid of the proxy's triangles, and barycentric weights.
#include "linkgi/Resolution.h"
#include "resolution/Decimate.h"

#include "linkgi/Error.h"
#include "cpu/Parallel.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>

namespace linkgi
{
namespace
{
/// The closest point of triangle abc to p as barycentric weights (Ericson, Real-Time
/// Collision Detection, 5.1.5): regions of the vertices, then of the edges, then the face.
std::array<float, 3> closestWeights(const Vec3f& p, const Vec3f& a, const Vec3f& b, const Vec3f& c)
{
  const Vec3f ab = b - a, ac = c - a, ap = p - a;
  const float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.f && d2 <= 0.f)
    return { 1.f, 0.f, 0.f };
  const Vec3f bp = p - b;
  const float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.f && d4 <= d3)
    return { 0.f, 1.f, 0.f };
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.f && d1 >= 0.f && d3 <= 0.f)
  {
    const float w = d1 / (d1 - d3);
    return { 1.f - w, w, 0.f };
  }
  const Vec3f cp = p - c;
  const float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.f && d5 <= d6)
    return { 0.f, 0.f, 1.f };
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.f && d2 >= 0.f && d6 <= 0.f)
  {
    const float w = d2 / (d2 - d6);
    return { 1.f - w, 0.f, w };
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.f && (d4 - d3) >= 0.f && (d5 - d6) >= 0.f)
  {
    const float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return { 0.f, 1.f - w, w };
  }
  const float denom = 1.f / (va + vb + vc);
  const float v = vb * denom, w = vc * denom;
  return { 1.f - v - w, v, w };
}

/// The proxy's triangles binned by their bounding boxes into cubic cells.
class TriangleGrid
{
public:
  explicit TriangleGrid(const Scene& proxy) : proxy(proxy)
  {
    positionBounds(proxy.positions, lo, hi);
    // About two triangles per occupied cell on a surface: cells of the mean edge length.
    const Vec3f extent = hi - lo;
    const float diagonal = std::max(length(extent), 1e-30f);
    cell = std::max(diagonal / 1024.f, diagonal / std::sqrt(float(proxy.triangleCount())));
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = std::max(1, std::min(1024, int(component(extent, a) / cell) + 1));
    }
    std::vector<std::uint32_t> counts(cellCount() + 1, 0);
    forEachCell([&](std::size_t c, Index) { ++counts[c + 1]; });
    for (std::size_t c = 1; c < counts.size(); ++c)
      counts[c] += counts[c - 1];
    offsets = counts;
    items.resize(offsets.back());
    forEachCell([&](std::size_t c, Index t) { items[counts[c]++] = t; });
    faceNormals.resize(proxy.triangleCount());
    for (std::size_t t = 0; t < faceNormals.size(); ++t)
    {
      const Triangle& tri = proxy.triangles[t];
      const Vec3f& a = proxy.positions[tri.v[0]];
      faceNormals[t] = cross(proxy.positions[tri.v[1]] - a, proxy.positions[tri.v[2]] - a);
    }
  }

  /// The nearest triangle to p whose face normal is within 90 degrees of n (any triangle
  /// when none is), and the closest point's weights.
  Index nearest(const Vec3f& p, const Vec3f& n, std::array<float, 3>& weights) const
  {
    const int home[3] = { clampCell(p.x - lo.x, 0), clampCell(p.y - lo.y, 1), clampCell(p.z - lo.z, 2) };
    // How far p lies inside its cell (0 outside the grid): every point of ring r >= 1 is at
    // least (r - 1) cells plus this far away. Most vertices lie on the proxy's surface, so
    // the search usually ends after ring 1 (27 cells) instead of ring 2 (125).
    float inside = cell;
    for (int a = 0; a < 3; ++a)
    {
      const float offset = component(p - lo, a) - float(home[a]) * cell;
      inside = std::min({ inside, offset, cell - offset });
    }
    inside = std::max(inside, 0.f);
    float best = std::numeric_limits<float>::max(), bestAny = best;
    Index found = kInvalidIndex, foundAny = kInvalidIndex;
    std::array<float, 3> w{}, wAny{};
    const int rings = std::max({ dims[0], dims[1], dims[2] });
    for (int r = 0; r <= rings; ++r)
    {
      const float reach = r == 0 ? 0.f : float(r - 1) * cell + inside;
      if (found != kInvalidIndex && reach * reach > best)
        break;
      // None facing the same way within twice the distance of the nearest: take that one.
      if (found == kInvalidIndex && foundAny != kInvalidIndex && reach * reach > 4.f * bestAny + 4.f * cell * cell)
        break;
      visitRing(home, r, [&](std::size_t c) {
        for (std::uint32_t i = offsets[c]; i < offsets[c + 1]; ++i)
        {
          const Index t = items[i];
          const Triangle& tri = proxy.triangles[t];
          const Vec3f &a = proxy.positions[tri.v[0]], &b = proxy.positions[tri.v[1]], &cc = proxy.positions[tri.v[2]];
          const std::array<float, 3> bw = closestWeights(p, a, b, cc);
          const Vec3f q = a * bw[0] + b * bw[1] + cc * bw[2];
          const float d = dot(q - p, q - p);
          if (dot(faceNormals[t], n) > 0.f ? d < best : false)
          {
            best = d, found = t, w = bw;
          }
          if (d < bestAny)
          {
            bestAny = d, foundAny = t, wAny = bw;
          }
        }
      });
    }
    weights = found != kInvalidIndex ? w : wAny;
    return found != kInvalidIndex ? found : foundAny;
  }

  /// The nearest facing triangle of every point of `points` (normals `normals`) that has one
  /// within `margin`, found from the triangles' side: each triangle offers itself to the
  /// points within `margin` of its bounding box, and a point keeps the smallest (distance,
  /// triangle) key. The nearest facing triangle at distance d <= margin has the point in
  /// its box grown by margin, so it was offered: the result is the nearest, exactly (ties:
  /// the lowest triangle). kInvalidIndex where none is that close. Far cheaper than a search
  /// per point when the points lie on the proxy's surface, as an input's vertices do: a
  /// point meets the few triangles around it instead of every triangle of 27 cells.
  std::vector<Index> nearestWithin(const std::vector<Vec3f>& points, const std::vector<Vec3f>& normals, float margin) const
  {
    // The points binned into the grid's cells (outside it: into the border cells).
    std::vector<std::uint32_t> first(cellCount() + 1, 0);
    std::vector<Index> order(points.size());
    const auto home = [&](const Vec3f& p) {
      return cellIndex(clampCell(p.x - lo.x, 0), clampCell(p.y - lo.y, 1), clampCell(p.z - lo.z, 2));
    };
    for (const Vec3f& p : points)
      ++first[home(p) + 1];
    for (std::size_t c = 1; c < first.size(); ++c)
      first[c] += first[c - 1];
    {
      std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
      for (std::size_t v = 0; v < points.size(); ++v)
        order[next[home(points[v])]++] = Index(v);
    }
    // In bin order, so that a cell's points are read in one sweep.
    std::vector<Vec3f> binned(points.size()), binnedNormals(points.size());
    for (std::size_t i = 0; i < order.size(); ++i)
    {
      binned[i] = points[order[i]];
      binnedNormals[i] = normals[order[i]];
    }
    // Keys: the distance's bits (non-negative floats order as their bits), then the triangle.
    std::vector<std::atomic<std::uint64_t>> best(points.size());
    for (auto& b : best)
      b.store(std::numeric_limits<std::uint64_t>::max(), std::memory_order_relaxed);
    const float margin2 = margin * margin;
    parallelRanges(proxy.triangleCount(), 256, [&](std::size_t begin, std::size_t end) {
      for (std::size_t t = begin; t < end; ++t)
      {
        const Triangle& tri = proxy.triangles[t];
        const Vec3f &a = proxy.positions[tri.v[0]], &b = proxy.positions[tri.v[1]], &c = proxy.positions[tri.v[2]];
        const Vec3f boxLo = Vec3f(std::min({ a.x, b.x, c.x }), std::min({ a.y, b.y, c.y }), std::min({ a.z, b.z, c.z })) - Vec3f(margin);
        const Vec3f boxHi = Vec3f(std::max({ a.x, b.x, c.x }), std::max({ a.y, b.y, c.y }), std::max({ a.z, b.z, c.z })) + Vec3f(margin);
        int cFirst[3], cLast[3];
        for (int k = 0; k < 3; ++k)
        {
          cFirst[k] = clampCell(component(boxLo - lo, k), k);
          cLast[k] = clampCell(component(boxHi - lo, k), k);
        }
        for (int z = cFirst[2]; z <= cLast[2]; ++z)
          for (int y = cFirst[1]; y <= cLast[1]; ++y)
            for (int x = cFirst[0]; x <= cLast[0]; ++x)
            {
              const std::size_t cell = cellIndex(x, y, z);
              for (std::uint32_t i = first[cell]; i < first[cell + 1]; ++i)
              {
                const Vec3f& p = binned[i];
                if (p.x < boxLo.x || p.y < boxLo.y || p.z < boxLo.z || p.x > boxHi.x || p.y > boxHi.y || p.z > boxHi.z ||
                  !(dot(faceNormals[t], binnedNormals[i]) > 0.f))
                  continue;
                const Index v = order[i];
                const std::array<float, 3> w = closestWeights(p, a, b, c);
                const Vec3f q = a * w[0] + b * w[1] + c * w[2];
                const float d = dot(q - p, q - p);
                if (!(d <= margin2))
                  continue;
                std::uint32_t bits;
                std::memcpy(&bits, &d, sizeof bits);
                const std::uint64_t key = (std::uint64_t(bits) << 32) | std::uint64_t(t);
                std::uint64_t now = best[v].load(std::memory_order_relaxed);
                while (key < now && !best[v].compare_exchange_weak(now, key, std::memory_order_relaxed))
                {
                }
              }
            }
      }
    });
    std::vector<Index> out(points.size());
    for (std::size_t v = 0; v < points.size(); ++v)
    {
      const std::uint64_t key = best[v].load(std::memory_order_relaxed);
      out[v] = key == std::numeric_limits<std::uint64_t>::max() ? kInvalidIndex : Index(key & 0xffffffffu);
    }
    return out;
  }

  /// The cells' edge length.
  float cellSize() const { return cell; }

private:
  static float component(const Vec3f& v, int a) { return a == 0 ? v.x : a == 1 ? v.y : v.z; }
  int clampCell(float offset, int a) const { return std::max(0, std::min(dims[a] - 1, int(offset / cell))); }
  std::size_t cellCount() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
  std::size_t cellIndex(int x, int y, int z) const { return (std::size_t(z) * dims[1] + y) * dims[0] + x; }

  template <typename F>
  void forEachCell(F f) const
  {
    for (std::size_t t = 0; t < proxy.triangleCount(); ++t)
    {
      int first[3], last[3];
      for (int a = 0; a < 3; ++a)
      {
        float mn = std::numeric_limits<float>::max(), mx = -mn;
        for (Index v : proxy.triangles[t].v)
        {
          mn = std::min(mn, component(proxy.positions[v], a));
          mx = std::max(mx, component(proxy.positions[v], a));
        }
        first[a] = clampCell(mn - component(lo, a), a);
        last[a] = clampCell(mx - component(lo, a), a);
      }
      for (int z = first[2]; z <= last[2]; ++z)
        for (int y = first[1]; y <= last[1]; ++y)
          for (int x = first[0]; x <= last[0]; ++x)
            f(cellIndex(x, y, z), Index(t));
    }
  }

  /// The cells at Chebyshev distance r from `home`.
  template <typename F>
  void visitRing(const int home[3], int r, F f) const
  {
    for (int z = std::max(0, home[2] - r); z <= std::min(dims[2] - 1, home[2] + r); ++z)
      for (int y = std::max(0, home[1] - r); y <= std::min(dims[1] - 1, home[1] + r); ++y)
      {
        const bool shell = std::abs(y - home[1]) == r || std::abs(z - home[2]) == r;
        const int x0 = std::max(0, home[0] - r), x1 = std::min(dims[0] - 1, home[0] + r);
        // Inside the shell's y, z range only its two x faces belong to the ring.
        const int step = shell || r == 0 ? 1 : 2 * r;
        for (int x = shell ? x0 : home[0] - r; x <= (shell ? x1 : home[0] + r); x += step)
        {
          if (x >= 0 && x < dims[0])
            f(cellIndex(x, y, z));
        }
      }
  }

  const Scene& proxy;
  Vec3f lo, hi;
  float cell = 1.f;
  int dims[3] = { 1, 1, 1 };
  std::vector<std::uint32_t> offsets;
  std::vector<Index> items;
  std::vector<Vec3f> faceNormals;
};
}

ProxyTransfer buildTransfer(const Scene& input, const Scene& proxy)
{
  if (proxy.triangleCount() == 0)
  {
    throw Error("The proxy has no triangles: nothing to carry its light from.");
  }
  const TriangleGrid grid(proxy);
  ProxyTransfer out;
  out.corners.resize(input.vertexCount());
  out.weights.resize(input.vertexCount());
  // Most vertices lie within a quarter of a cell of a facing triangle (98% of a 1M-vertex
  // isosurface's on a 30k proxy): found from the triangles' side; the others search the grid
  // around them.
  const std::vector<Index> near = grid.nearestWithin(input.positions, input.normals, 0.25f * grid.cellSize());
  parallelRanges(input.vertexCount(), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      Index t = near[v];
      if (t == kInvalidIndex)
      {
        t = grid.nearest(input.positions[v], input.normals[v], out.weights[v]);
      }
      else
      {
        const Triangle& tri = proxy.triangles[t];
        out.weights[v] = closestWeights(input.positions[v], proxy.positions[tri.v[0]], proxy.positions[tri.v[1]],
          proxy.positions[tri.v[2]]);
      }
      out.corners[v] = proxy.triangles[t];
    }
  });
  return out;
}

std::vector<Vec3f> ProxyTransfer::apply(const std::vector<Vec3f>& values) const
{
  std::vector<Vec3f> out(corners.size());
  parallelRanges(out.size(), 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      const Triangle& t = corners[v];
      out[v] = values[t.v[0]] * weights[v][0] + values[t.v[1]] * weights[v][1] + values[t.v[2]] * weights[v][2];
    }
  });
  return out;
}
}
