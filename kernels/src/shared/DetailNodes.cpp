#include "shared/DetailNodes.h"

#include "cpu/Parallel.h"
#include "shared/Surface.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace linkgi
{
namespace
{
constexpr int kMostSteps = 64; // 2,142 nodes: a triangle larger still is a budget's worth

/// Grid steps of a triangle whose longest edge is `longest` at `spacing`: 0 below two.
int stepsFor(float longest, float spacing)
{
  const float n = std::ceil(longest / spacing);
  return n < 2.f ? 0 : int(std::min(n, float(kMostSteps)));
}

std::size_t nodesOf(int n)
{
  return n >= 2 ? std::size_t(n + 1) * std::size_t(n + 2) / 2 - 3 : 0;
}
}

DetailGrid DetailNodes::grid(std::size_t elementCount, const Index* firstCopy, const std::uint16_t* stepsCopy) const
{
  DetailGrid g;
  if (!empty())
  {
    g.first = firstCopy;
    g.steps = stepsCopy;
    g.columnBase = Index(elementCount);
    g.nodesPerSide = Index(nodes.size());
  }
  return g;
}

std::size_t detailNodeBudget(std::size_t vertices)
{
  // A light move traces the nodes' shadow rays beside the vertices' (the CAD motor of 1,710
  // points: 1.1 ms without nodes, 2.3 ms with 16k, on 2 cores) and the links that reach
  // them spread over more columns. The motor's error against the path tracer: 13.6%
  // without nodes, 9.2% with 2,000, 8.2-8.7% with 4,096 to 32,000, 7.9% with 100,000.
  return std::max<std::size_t>(vertices, 4096);
}

std::size_t detailNodeBound(std::size_t vertices, std::size_t triangles)
{
  return std::min(detailNodeBudget(vertices), nodesOf(kMostSteps) * ((triangles + 1) / 2));
}

DetailNodes detailNodes(const Scene& scene, std::size_t budget)
{
  DetailNodes out;
  const std::size_t nt = scene.triangles.size();
  if (nt == 0)
  {
    return out;
  }
  std::vector<float> longest(nt, 0.f);
  for (std::size_t t = 0; t < nt; ++t)
  {
    const Triangle& tri = scene.triangles[t];
    float l2 = 0.f;
    for (int k = 0; k < 3; ++k)
    {
      const Vec3f d = scene.positions[tri.v[(k + 1) % 3]] - scene.positions[tri.v[k]];
      l2 = std::max(l2, dot(d, d));
    }
    const float l = std::sqrt(l2);
    longest[t] = std::isfinite(l) ? l : 0.f;
  }
  // The grids go on the triangles larger than the mesh's own detail: twice its median
  // triangle or more (a mesh of even triangles gets none, however coarse), and twice 1/256
  // of its diagonal or more. Their steps are as fine as the budget lets, down to that
  // 1/256.
  std::vector<float> sorted = longest;
  std::nth_element(sorted.begin(), sorted.begin() + nt / 2, sorted.end());
  const float median = sorted[nt / 2];
  std::vector<float>().swap(sorted);
  const float finest = sceneExtent(scene).diagonal / 256.f;
  if (!(finest > 0.f) || !std::isfinite(finest))
  {
    return out;
  }
  std::vector<float> candidates;
  float most = 0.f;
  for (float& l : longest)
  {
    if (l >= 2.f * std::max(median, finest))
    {
      candidates.push_back(l);
      most = std::max(most, l);
    }
    else
    {
      l = 0.f; // no grid
    }
  }
  if (candidates.empty())
  {
    return out;
  }
  // Whether the grids at `spacing` stay within the budget (counting stops once they do not).
  const auto fits = [&](float spacing) {
    std::size_t c = 0;
    for (float l : candidates)
    {
      c += nodesOf(stepsFor(l, spacing));
      if (c > budget)
      {
        return false;
      }
    }
    return true;
  };
  // The node count falls as the spacing grows: bisect on its logarithm between the finest
  // spacing and the longest edge (where no triangle spans two steps), to within 0.2%.
  float spacing = finest;
  if (!fits(finest))
  {
    float a = std::log(finest), b = std::log(most);
    while (b - a > 2e-3f)
    {
      const float m = 0.5f * (a + b);
      (fits(std::exp(m)) ? b : a) = m;
    }
    spacing = std::exp(b);
  }
  out.spacing = spacing;
  out.first.assign(nt, kInvalidIndex);
  out.steps.assign(nt, 0);
  for (std::size_t t = 0; t < nt; ++t)
  {
    const int n = longest[t] > 0.f ? stepsFor(longest[t], spacing) : 0;
    if (n < 2)
    {
      continue;
    }
    out.steps[t] = std::uint16_t(n);
    out.first[t] = Index(out.nodes.size());
    for (int j = 0; j <= n; ++j)
    {
      for (int i = 0; i <= n - j; ++i)
      {
        const bool corner = (j == 0 && (i == 0 || i == n)) || (i == 0 && j == n);
        if (!corner)
        {
          out.nodes.push_back({ Index(t), float(i) / float(n), float(j) / float(n) });
        }
      }
    }
  }
  if (out.nodes.empty())
  {
    return DetailNodes();
  }
  return out;
}

std::vector<Vec3f> detailNodeDirect(const Scene& scene, const DetailNodes& detail,
  const std::vector<RayOrigin>& origins, const std::vector<Vec3f>& faceNormals,
  const RayTracer& tracer, bool twoSided, std::uint64_t* shadowRays)
{
  const std::size_t n = detail.nodes.size();
  std::vector<Vec3f> out(detail.columns(twoSided));
  std::atomic<std::uint64_t> rays{ 0 };
  parallelRanges(out.size(), 256, [&](std::size_t begin, std::size_t end) {
    std::uint64_t traced = 0;
    const auto occluded = [&tracer, &traced](const Ray& ray) {
      ++traced;
      return AnyHit{ tracer }(ray);
    };
    for (std::size_t k = begin; k < end; ++k)
    {
      out[k] = detailNodeDirect(detail.nodes[k % n], k >= n ? 1 : 0, scene.triangles.data(),
        scene.positions.data(), scene.normals.data(), faceNormals.data(), origins.data(), scene.lights.data(), Index(scene.lights.size()), occluded);
    }
    rays += traced;
  });
  if (shadowRays)
  {
    *shadowRays += rays;
  }
  return out;
}

void detailNodeRadiance(const Scene& scene, const DetailNodes& detail, bool twoSided, const Vec3f* direct,
  const Vec3f* nodeDirect, std::size_t columnBase, Vec3f* radiance)
{
  const std::size_t n = detail.nodes.size();
  parallelRanges(detail.columns(twoSided), 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k)
    {
      const DetailNode& node = detail.nodes[k % n];
      radiance[columnBase + k] = detailNodeRadiance(node, scene.triangles[node.triangle], k >= n ? 1 : 0,
        Index(scene.vertexCount()), [radiance](Index e) { return radiance[e]; }, direct, scene.albedo.data(),
        nodeDirect[k]);
    }
  });
}
}
