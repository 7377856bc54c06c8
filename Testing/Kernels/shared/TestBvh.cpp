// The GPU's BVH (linear BVH build steps, node layout, traversal), run on the CPU: it must
// find exactly the hits a brute-force loop over all triangles finds, before and after refit.
#include "SceneFixtures.h"

#include "shared/BvhBuild.h"
#include "linkgi/Scenes.h"

#include <gtest/gtest.h>

#include <random>

using namespace linkgi;

namespace
{
/// Closest hit over every triangle (AnyHit: any hit), with the traversal's own triangle test.
bool bruteForce(const Scene& s, const Ray& ray, Hit& hit, bool anyHit)
{
  const bvh::PreparedRay r = bvh::prepare(ray);
  float tfar = ray.tfar;
  hit = Hit{};
  for (Index t = 0; t < s.triangleCount(); ++t)
  {
    const Index* v = s.triangles[t].v;
    const BvhTriangle tri = bvh::makeTriangle(s.positions[v[0]], s.positions[v[1]], s.positions[v[2]], t);
    float th, u, w;
    if (bvh::intersectTriangle(r, tri, tfar, th, u, w))
    {
      tfar = th;
      hit = Hit{ t, u, w, th };
      if (anyHit)
      {
        return true;
      }
    }
  }
  return hit.triangle != kInvalidIndex;
}

/// Rays from random points of the scene box in random directions, some with short tfar.
std::vector<Ray> randomRays(const Scene& s, std::size_t count, unsigned seed)
{
  bvh::Box box;
  for (const Vec3f& p : s.positions)
  {
    box.grow(p);
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Ray> rays(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    Ray& r = rays[i];
    r.origin = { box.lo.x + u(rng) * (box.hi.x - box.lo.x), box.lo.y + u(rng) * (box.hi.y - box.lo.y),
      box.lo.z + u(rng) * (box.hi.z - box.lo.z) };
    r.direction = normalize(Vec3f(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
    r.tfar = i % 3 == 0 ? 0.5f : 3.0e38f;
  }
  return rays;
}

void expectSameHitsAsBruteForce(const Scene& s, const HostBvh& bvh, unsigned seed)
{
  int mismatches = 0;
  for (const Ray& ray : randomRays(s, 3000, seed))
  {
    Hit expected, found;
    const bool hitExpected = bruteForce(s, ray, expected, false);
    const bool hitFound = bvh::traverse<false>(bvh.view(), ray, found);
    ASSERT_EQ(hitFound, hitExpected);
    if (hitExpected && found.triangle != expected.triangle)
    {
      // Only a tie (the same distance to two triangles sharing an edge) may differ.
      EXPECT_NEAR(found.t, expected.t, 1e-5f * std::max(1.f, expected.t));
      ++mismatches;
    }
    Hit any;
    EXPECT_EQ(bvh::traverse<true>(bvh.view(), ray, any), hitExpected);
  }
  EXPECT_LT(mismatches, 10);
}

/// Every leaf is reached exactly once from the root and every child box holds its subtree.
void expectWellFormed(const HostBvh& bvh)
{
  const std::size_t n = bvh.triangles.size();
  std::vector<int> seen(n, 0);
  std::vector<int> stack{ 0 };
  while (!stack.empty())
  {
    const BvhNode& node = bvh.nodes[stack.back()];
    const int self = stack.back();
    stack.pop_back();
    for (int c = 0; c < 2; ++c)
    {
      const float lo[3] = { c ? node.lo1x : node.lo0x, c ? node.lo1y : node.lo0y, c ? node.lo1z : node.lo0z };
      const float hi[3] = { c ? node.hi1x : node.hi0x, c ? node.hi1y : node.hi0y, c ? node.hi1z : node.hi0z };
      if (node.child[c] < 0)
      {
        const int leaf = ~node.child[c];
        ++seen[leaf];
        EXPECT_EQ(bvh.leafParents[leaf], self);
        const bvh::Box b = bvh::triangleBox(bvh.triangles[leaf]);
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_LE(lo[k], b.lo[k]);
          EXPECT_GE(hi[k], b.hi[k]);
        }
      }
      else
      {
        EXPECT_EQ(bvh.nodes[node.child[c]].parent, self);
        stack.push_back(node.child[c]);
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    ASSERT_EQ(seen[i], 1) << "leaf " << i;
  }
}
}

TEST(Bvh, LinearBvhIsWellFormed)
{
  const Scene s = makeStandardScene("tearoom");
  HostBvh bvh;
  bvh.build(s.positions, s.triangles);
  ASSERT_EQ(bvh.nodes.size(), s.triangleCount() - 1);
  EXPECT_EQ(bvh.nodes[0].parent, -1);
  expectWellFormed(bvh);
}

TEST(Bvh, TraversalFindsTheBruteForceHits)
{
  const Scene s = test::roomWithBlock();
  HostBvh bvh;
  bvh.build(s.positions, s.triangles);
  expectSameHitsAsBruteForce(s, bvh, 1);
}

TEST(Bvh, RefitFollowsMovedVertices)
{
  Scene s = test::roomWithBlock();
  HostBvh bvh;
  bvh.build(s.positions, s.triangles);
  for (Vec3f& p : s.positions)
  {
    p = Vec3f(p.x * 1.3f + 0.2f * p.y, p.y * 0.8f, p.z + 0.1f * p.x * p.x);
  }
  bvh.refit(s.positions, s.triangles);
  expectWellFormed(bvh);
  expectSameHitsAsBruteForce(s, bvh, 2);
}

TEST(Bvh, SingleTriangleAndDuplicateCentroids)
{
  // One triangle: the root is a leaf. Then many triangles with one Morton code: the index
  // tie-break must still give a valid tree.
  Scene one;
  one.positions = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } };
  one.triangles = { Triangle{ { 0, 1, 2 } } };
  HostBvh single;
  single.build(one.positions, one.triangles);
  Ray down;
  down.origin = { 0.2f, 0.2f, 1.f };
  down.direction = { 0, 0, -1 };
  Hit h;
  ASSERT_TRUE(bvh::traverse<false>(single.view(), down, h));
  EXPECT_EQ(h.triangle, 0u);
  EXPECT_NEAR(h.t, 1.f, 1e-6f);

  Scene stack;
  for (int i = 0; i < 40; ++i)
  {
    const Index b = Index(stack.positions.size());
    const float z = 0.001f * i;
    stack.positions.insert(stack.positions.end(), { { -1, -1, z }, { 1, -1, z }, { 0, 2, z } });
    stack.triangles.push_back(Triangle{ { b, b + 1, b + 2 } });
  }
  HostBvh bvh;
  bvh.build(stack.positions, stack.triangles);
  expectWellFormed(bvh);
  ASSERT_TRUE(bvh::traverse<false>(bvh.view(), down, h));
  EXPECT_EQ(h.triangle, 39u); // the highest plane is the closest from above
}

TEST(Bvh, CpuTracerOfThisBuildTraces)
{
  const Scene s = test::roomWithBlock();
  std::unique_ptr<RayTracer> tracers[] = { createBvhRayTracer(), createCpuRayTracer() };
  for (const auto& tracer : tracers)
  {
    tracer->build(s.positions, s.triangles);
    const std::vector<Ray> rays = randomRays(s, 500, 3);
    std::vector<Hit> hits(rays.size());
    tracer->trace(rays.data(), hits.data(), rays.size());
    int agree = 0;
    for (std::size_t i = 0; i < rays.size(); ++i)
    {
      Hit expected;
      bruteForce(s, rays[i], expected, false);
      agree += hits[i].triangle == expected.triangle ||
        std::fabs(hits[i].t - expected.t) < 1e-4f * std::max(1.f, expected.t);
    }
    EXPECT_GE(agree, int(rays.size()) - 2) << tracer->name();
  }
}

TEST(Bvh, SahTreeIsWellFormedAndFindsTheSameHits)
{
  const Scene s = test::roomWithBlock();
  HostBvh sah, linear;
  sah.buildSah(s.positions, s.triangles);
  linear.build(s.positions, s.triangles);
  expectWellFormed(sah);
  expectSameHitsAsBruteForce(s, sah, 4);
}
