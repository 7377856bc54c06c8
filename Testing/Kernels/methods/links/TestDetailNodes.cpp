#include "CudaFixtures.h"
#include "SceneFixtures.h"

#include "linkgi/Solver.h"
#include "shared/DetailNodes.h"
#include "shared/Surface.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <set>

using namespace linkgi;

namespace
{
/// A floor of 2 triangles 4 m wide, a wall of 8 x 8 cells beside it and a box of 1 x 1 x 1
/// cells: triangles of many sizes.
Scene floorWallAndBox()
{
  MeshBuilder b;
  b.addQuadGrid({ -2, 0, -2 }, { 0, 0, 4 }, { 4, 0, 0 }, 1, 1, Vec3f(0.5f));
  b.addQuadGrid({ -2, 0, -2 }, { 4, 0, 0 }, { 0, 1, 0 }, 8, 8, Vec3f(0.5f));
  b.addBox({ 0, 0, 0 }, { 0.5f, 0.5f, 0.5f }, 0.5f, Vec3f(0.5f));
  return b.take();
}

/// The barycentrics on triangle t of column `c` (a corner's element or one of t's nodes).
std::array<float, 2> columnUv(const DetailNodes& d, const DetailGrid& g, const Triangle& tri, Index c,
  Index vertexCount)
{
  if (c < g.columnBase)
  {
    const Index v = c % vertexCount;
    return { v == tri.v[1] ? 1.f : 0.f, v == tri.v[2] ? 1.f : 0.f };
  }
  const DetailNode& node = d.nodes[(c - g.columnBase) % g.nodesPerSide];
  return { node.u, node.v };
}
}

TEST(TestDetailNodes, EveryGridPointIsOneColumnAndItsOwnCell)
{
  const Scene s = floorWallAndBox();
  const DetailNodes d = detailNodes(s, 4096);
  ASSERT_FALSE(d.empty());
  EXPECT_LE(d.nodes.size(), 4096u);
  const Index nv = Index(s.vertexCount());
  for (bool back : { false, true })
  {
    const std::size_t elements = Elements{ nv, true }.count();
    const DetailGrid g = d.grid(elements);
    std::set<Index> seen;
    for (std::size_t t = 0; t < s.triangles.size(); ++t)
    {
      const int n = d.steps[t];
      if (n < 2)
      {
        continue;
      }
      for (int j = 0; j <= n; ++j)
      {
        for (int i = 0; i <= n - j; ++i)
        {
          Index column[3];
          float weight[3];
          detailCell(g, Index(t), s.triangles[t], float(i) / n, float(j) / n, back, nv, column, weight);
          const int k = int(std::max_element(weight, weight + 3) - weight);
          ASSERT_NEAR(weight[k], 1.f, 1e-5f) << "triangle " << t << " point " << i << ", " << j;
          const Index c = column[k];
          const bool corner = (j == 0 && (i == 0 || i == n)) || (i == 0 && j == n);
          if (corner)
          {
            EXPECT_EQ(c, s.triangles[t].v[i == n ? 1 : j == n ? 2 : 0] + (back ? nv : 0));
            continue;
          }
          EXPECT_TRUE(seen.insert(c).second) << "column " << c << " twice";
          const Index sideBase = g.columnBase + (back ? g.nodesPerSide : 0);
          ASSERT_GE(c, sideBase);
          ASSERT_LT(c, sideBase + g.nodesPerSide);
          const DetailNode& node = d.nodes[c - sideBase];
          EXPECT_EQ(node.triangle, t);
          EXPECT_NEAR(node.u, float(i) / n, 1e-6f);
          EXPECT_NEAR(node.v, float(j) / n, 1e-6f);
        }
      }
    }
    EXPECT_EQ(seen.size(), d.nodes.size()) << "every node is some triangle's grid point";
  }
  // One spacing for the whole mesh: no cell edge longer. The floor is the only triangle
  // twice the median's size (the wall's cells, the box's faces): the only one with a grid.
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
  {
    float longest = 0.f;
    for (int k = 0; k < 3; ++k)
    {
      const Vec3f e = s.positions[s.triangles[t].v[(k + 1) % 3]] - s.positions[s.triangles[t].v[k]];
      longest = std::max(longest, std::sqrt(dot(e, e)));
    }
    if (d.steps[t] >= 2)
    {
      EXPECT_LE(longest / d.steps[t], d.spacing * 1.0001f) << "triangle " << t;
      EXPECT_LT(t, 2u) << "only the floor's two triangles";
    }
  }
  EXPECT_GE(d.steps[0], 8) << "the floor";
}

TEST(TestDetailNodes, AHitReadsALinearFunctionExactly)
{
  // The cell's weights are barycentric within it, so a function linear over the triangle
  // is read exactly anywhere on it, from the corners and the nodes alike.
  const Scene s = floorWallAndBox();
  const DetailNodes d = detailNodes(s, 4096);
  const Index nv = Index(s.vertexCount());
  const DetailGrid g = d.grid(nv);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.f, 1.f);
  const auto f = [](float u, float v) { return 0.3f + 2.f * u - 1.5f * v; };
  int hits = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
  {
    if (d.steps[t] < 2)
    {
      continue;
    }
    for (int k = 0; k < 200; ++k, ++hits)
    {
      float u = uniform(random), v = uniform(random);
      if (u + v > 1.f)
      {
        u = 1.f - u;
        v = 1.f - v;
      }
      Index column[3];
      float weight[3];
      detailCell(g, Index(t), s.triangles[t], u, v, false, nv, column, weight);
      float read = 0.f, sum = 0.f;
      for (int c = 0; c < 3; ++c)
      {
        const auto uv = columnUv(d, g, s.triangles[t], column[c], nv);
        read += weight[c] * f(uv[0], uv[1]);
        sum += weight[c];
        EXPECT_GE(weight[c], -1e-5f);
      }
      EXPECT_NEAR(sum, 1.f, 1e-5f);
      EXPECT_NEAR(read, f(u, v), 1e-4f) << "triangle " << t << " at " << u << ", " << v;
    }
  }
  EXPECT_GT(hits, 0);
}

TEST(TestDetailNodes, OnlyTrianglesLargerThanTheMeshsDetailGetGrids)
{
  // A mesh of even triangles has no detail finer than them: none, fine or coarse.
  EXPECT_TRUE(detailNodes(test::twoSquares(false, 200), 1u << 20).empty());
  EXPECT_TRUE(detailNodes(test::twoSquares(false, 2), 1u << 20).empty());
  // A coarse floor beside fine parts: its grid, as fine as the budget lets.
  const DetailNodes floor = detailNodes(floorWallAndBox(), 1000);
  EXPECT_FALSE(floor.empty());
  EXPECT_LE(floor.nodes.size(), 1000u);
  EXPECT_GT(floor.nodes.size(), 500u) << "the budget is used, not a fraction of it";
}

namespace
{
/// The plate's indirect light with `method` on `backend` over the reference's
/// (test::plateInAPoolOfLight): a link from the plate that hits the floor, or an implicit
/// link's surface hit there, must read the light where it lands. From the floor's dark
/// corners alone, the plate got none.
void expectPlateLitAsTheReference(Backend backend, Method method = Method::Links)
{
  Index plate = 0;
  const Scene s = test::plateInAPoolOfLight(plate);
  SolverOptions o;
  o.method = method;
  o.backend = backend;
  o.bounces = 1;
  o.raysPerVertex = 1024;
  Solver solver;
  const Solution& links = solver.update(s, o);
  ASSERT_EQ(solver.stats().backend, backend == Backend::Cpu ? "cpu" : "cuda") << solver.stats().backendNote;
  const auto [mean, reference] = test::meanIndirectAndReference(s, links.indirect, plate);
  std::printf("plate in a pool of light (%s, method %d): mean indirect %.5f, the reference %.5f\n",
    solver.stats().backend.c_str(), int(method), mean, reference);
  EXPECT_GT(reference, 0.0);
  EXPECT_NEAR(mean / reference, 1.0, 0.1);
}
}

TEST(TestDetailNodes, LinksSeeTheLightOnALargeTriangleWhoseCornersAreDark)
{
  expectPlateLitAsTheReference(Backend::Cpu);
}

TEST(TestDetailNodes, ImplicitLinksSeeTheLightOnALargeTriangleWhoseCornersAreDark)
{
  // The floor's four vertices are the plate's near leaves, drawn from their surface; the
  // two behind the plate's plane reach in front of it (ClusterTree::extent), and without
  // them the bins towards the floor beside the plate's foot saw nothing (28% low).
  expectPlateLitAsTheReference(Backend::Cpu, Method::ImplicitVisibility);
}

TEST(TestDetailNodes, ImplicitLinksSeeTheLightOnALargeTriangleWhoseCornersAreDarkOnTheGpu)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  expectPlateLitAsTheReference(Backend::Cuda, Method::ImplicitVisibility);
  Index plate = 0;
  SolverOptions o;
  o.method = Method::ImplicitVisibility;
  test::expectBackendsAgree(test::plateInAPoolOfLight(plate), o, 2e-3f);
}

TEST(TestDetailNodes, LinksSeeTheLightOnALargeTriangleWhoseCornersAreDarkOnTheGpu)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  expectPlateLitAsTheReference(Backend::Cuda);
  // Both sides' nodes, on both backends alike.
  Index plate = 0;
  SolverOptions o;
  o.twoSided = true;
  test::expectBackendsAgree(test::plateInAPoolOfLight(plate), o, 2e-3f);
}
