// Our BVH on the CPU: the GPU's build steps run as loops, the GPU's traversal as plain C++.
// Builds without Embree trace with it; tests use it to check the GPU's layout and build.
#include "shared/BvhBuild.h"

#include "linkgi/Error.h"
#include "cpu/Parallel.h"

#include <algorithm>
#include <numeric>

namespace linkgi
{
void HostBvh::build(const std::vector<Vec3f>& positions, const std::vector<Triangle>& tris)
{
  const std::size_t n = tris.size();
  nodes.assign(n > 1 ? n - 1 : 1, BvhNode{});
  leafParents.assign(n, -1);
  triangles.resize(n);
  if (n == 0)
  {
    return;
  }
  bvh::Box scene;
  for (const Vec3f& p : positions)
  {
    scene.grow(p);
  }
  const Vec3f extent = scene.hi - scene.lo;
  const Vec3f inv(extent.x > 0.f ? 1.f / extent.x : 0.f, extent.y > 0.f ? 1.f / extent.y : 0.f,
    extent.z > 0.f ? 1.f / extent.z : 0.f);
  std::vector<std::pair<std::uint64_t, Index>> keyed(n);
  parallelRanges(n, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      const Triangle& t = tris[i];
      keyed[i] = { bvh::mortonKey(positions[t.v[0]], positions[t.v[1]], positions[t.v[2]], scene.lo, inv),
        Index(i) };
    }
  });
  // (key, index) order is what the GPU's stable radix sort of keys gives.
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint64_t> keys(n);
  for (std::size_t p = 0; p < n; ++p)
  {
    keys[p] = keyed[p].first;
    triangles[p].id = keyed[p].second;
  }
  parallelRanges(n > 1 ? n - 1 : 0, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      bvh::buildInternalNode(keys.data(), int(n), int(i), nodes.data(), leafParents.data());
    }
  });
  refit(positions, tris);
}

void HostBvh::refit(const std::vector<Vec3f>& positions, const std::vector<Triangle>& tris)
{
  for (BvhTriangle& leaf : triangles)
  {
    const Triangle& t = tris[leaf.id];
    leaf = bvh::makeTriangle(positions[t.v[0]], positions[t.v[1]], positions[t.v[2]], leaf.id);
  }
  std::vector<unsigned> arrivals(nodes.size(), 0u);
  for (std::size_t leaf = 0; triangles.size() > 1 && leaf < triangles.size(); ++leaf)
  {
    bvh::propagateBounds(nodes.data(), leafParents.data(), triangles.data(), arrivals.data(), int(leaf));
  }
}

BvhView HostBvh::view() const
{
  BvhView v;
  v.nodes = nodes.data();
  v.triangles = triangles.data();
  v.root = triangles.size() > 1 ? 0 : ~0;
  v.triangleCount = Index(triangles.size());
  return v;
}

namespace
{
class BvhRayTracer final : public RayTracer
{
public:
  const char* name() const override { return "lbvh"; }

  void build(const std::vector<Vec3f>& positions, const std::vector<Triangle>& tris) override
  {
    triangles = tris;
    bvh.build(positions, triangles);
  }

  void refit(const std::vector<Vec3f>& positions) override
  {
    bvh.refit(positions, triangles);
  }

  void trace(const Ray* rays, Hit* hits, std::size_t count) const override
  {
    const BvhView view = bvh.view();
    for (std::size_t i = 0; i < count; ++i)
    {
      bvh::traverse<false>(view, rays[i], hits[i]);
    }
  }

  void occluded(const Ray* rays, std::uint8_t* occluded, std::size_t count) const override
  {
    const BvhView view = bvh.view();
    for (std::size_t i = 0; i < count; ++i)
    {
      Hit h;
      occluded[i] = bvh::traverse<true>(view, rays[i], h) ? 1 : 0;
    }
  }

private:
  HostBvh bvh;
  std::vector<Triangle> triangles;
};
}

std::unique_ptr<RayTracer> createBvhRayTracer()
{
  return std::make_unique<BvhRayTracer>();
}

std::unique_ptr<RayTracer> createCpuRayTracer()
{
#if LINKGI_HAVE_EMBREE
  return createEmbreeRayTracer();
#else
  return createBvhRayTracer();
#endif
}

#if !LINKGI_HAVE_EMBREE
std::unique_ptr<RayTracer> createEmbreeRayTracer()
{
  throw Error("This build has no Embree; use createCpuRayTracer().");
}
#endif
}
