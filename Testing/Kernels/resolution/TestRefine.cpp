// Adaptive refinement: the split keeps the input's vertices, surface and edges,
// stops at the vertex budget, and brings a mesh of two triangles per wall to the accuracy of
// a fine one against the path-traced reference. The scenes are test::roomWithBlock: cell
// 10 gives two triangles per face (48 vertices).
#include "CudaFixtures.h"
#include "SceneFixtures.h"

#include "linkgi/Error.h"
#include "shared/Metrics.h"
#include "linkgi/Resolution.h"
#include "resolution/Decimate.h"
#include "resolution/Refinement.h"
#include "methods/reference/Reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <numeric>

using namespace linkgi;
using test::errorOf;

namespace
{
double triangleArea(const Scene& s, const Triangle& t)
{
  const Vec3f e1 = s.positions[t.v[1]] - s.positions[t.v[0]];
  const Vec3f e2 = s.positions[t.v[2]] - s.positions[t.v[0]];
  const Vec3f c = cross(e1, e2);
  return 0.5 * std::sqrt(double(dot(c, c)));
}

std::vector<Vec3f> total(const std::vector<Vec3f>& direct, const std::vector<Vec3f>& indirect)
{
  std::vector<Vec3f> sum(direct.size());
  for (std::size_t i = 0; i < sum.size(); ++i)
  {
    sum[i] = direct[i] + indirect[i];
  }
  return sum;
}
}

TEST(Refine, SplitKeepsInputVerticesSurfaceAndEdges)
{
  const Scene input = test::roomWithBlock(10.f);
  RefinedScene r;
  r.scene = input;
  r.inputVertices = input.vertexCount();
  r.sourceTriangle.resize(input.triangleCount());
  std::iota(r.sourceTriangle.begin(), r.sourceTriangle.end(), Index(0));
  // Every edge of the first triangle, one edge of the second, two of the third.
  const auto& t = input.triangles;
  const std::vector<std::pair<Index, Index>> edges = { { t[0].v[0], t[0].v[1] },
    { t[0].v[1], t[0].v[2] }, { t[0].v[2], t[0].v[0] }, { t[5].v[0], t[5].v[1] },
    { t[9].v[1], t[9].v[0] }, { t[9].v[2], t[9].v[1] } };
  splitEdges(r, edges);
  ASSERT_GT(r.scene.vertexCount(), input.vertexCount());
  for (std::size_t v = 0; v < input.vertexCount(); ++v)
  {
    ASSERT_EQ(r.scene.positions[v], input.positions[v]);
    ASSERT_EQ(r.scene.normals[v], input.normals[v]);
    ASSERT_EQ(r.scene.albedo[v], input.albedo[v]);
  }
  for (std::size_t k = 0; k < r.midpointOf.size(); ++k)
  {
    const Index v = Index(input.vertexCount() + k), a = r.midpointOf[k][0], b = r.midpointOf[k][1];
    ASSERT_LT(a, v);
    ASSERT_LT(b, v);
    EXPECT_EQ(r.scene.positions[v], (r.scene.positions[a] + r.scene.positions[b]) * 0.5f);
    EXPECT_EQ(r.scene.albedo[v], (r.scene.albedo[a] + r.scene.albedo[b]) * 0.5f);
  }
  // Each input triangle's area is covered exactly by its pieces, with its winding.
  std::map<Index, double> area;
  for (std::size_t k = 0; k < r.scene.triangleCount(); ++k)
  {
    const Triangle& piece = r.scene.triangles[k];
    const Triangle& source = input.triangles[r.sourceTriangle[k]];
    area[r.sourceTriangle[k]] += triangleArea(r.scene, piece);
    const Vec3f np = cross(r.scene.positions[piece.v[1]] - r.scene.positions[piece.v[0]],
      r.scene.positions[piece.v[2]] - r.scene.positions[piece.v[0]]);
    const Vec3f ns = cross(input.positions[source.v[1]] - input.positions[source.v[0]],
      input.positions[source.v[2]] - input.positions[source.v[0]]);
    EXPECT_GT(dot(np, ns), 0.f) << "piece " << k << " lost its source's winding";
  }
  for (std::size_t k = 0; k < input.triangleCount(); ++k)
  {
    EXPECT_NEAR(area[Index(k)], triangleArea(input, input.triangles[k]), 1e-6) << "triangle " << k;
  }
  // A triangle with k split edges becomes k + 1 pieces, its neighbours across them too.
  std::size_t expected = 0;
  for (const Triangle& tri : input.triangles)
  {
    ++expected;
    for (int i = 0; i < 3; ++i)
    {
      const Index a = tri.v[i], b = tri.v[(i + 1) % 3];
      for (const auto& e : edges)
      {
        expected += (e.first == a && e.second == b) || (e.first == b && e.second == a);
      }
    }
  }
  EXPECT_EQ(r.scene.triangleCount(), expected);
  EXPECT_EQ(r.scene.vertexCount(), input.vertexCount() + edges.size());
}

TEST(Refine, TwoTrianglesPerWallReachTheFineMeshAccuracy)
{
  // Reference on a fine grid of the same surfaces.
  const Scene fine = test::roomWithBlock(0.25f);
  ReferenceOptions ro;
  ro.pathsPerVertex = 1024;
  const ReferenceSolution reference = solveReference(fine, ro);
  const std::vector<Vec3f> truth = total(reference.direct, reference.indirect);
  const std::vector<float> areas = vertexAreas(fine);
  const auto errorOn = [&](const Scene& mesh, const Solution& solution)
  {
    Scene checked = mesh;
    validateScene(checked);
    const ProxyTransfer onFine = buildTransfer(fine, checked);
    return relativeRmse(onFine.apply(total(solution.direct, solution.indirect)), truth, areas)
      .relRmseLuminance;
  };

  const Scene coarse = test::roomWithBlock(10.f);
  SolverOptions options;
  options.backend = Backend::Cpu;
  Solver plain;
  const float before = errorOn(coarse, plain.update(coarse, options));

  RefiningSolver refining;
  RefinementOptions refinement;
  refinement.tolerance = 0.1f;
  refinement.rounds = 8;
  refinement.maxVertices = 6000;
  refining.update(coarse, options, refinement);
  const float after = errorOn(refining.refined().scene, refining.solution());
  std::cout << "two triangles per wall: relative RMSE of E " << before << " -> " << after << " with "
            << refining.refined().scene.vertexCount() << " vertices after "
            << refining.splitsPerRound().size() << " rounds\n";
  EXPECT_LE(after, 0.05f);
  EXPECT_LT(after, 0.5f * before);
  EXPECT_LE(refining.refined().scene.vertexCount(), refinement.maxVertices);
}

TEST(Refine, StopsAtTheVertexBudgetAndKeepsTheLastResultOnAbort)
{
  const Scene coarse = test::roomWithBlock(10.f);
  SolverOptions options;
  options.backend = Backend::Cpu;
  options.raysPerVertex = 64;
  RefiningSolver refining;
  RefinementOptions refinement;
  refinement.maxVertices = coarse.vertexCount() + 10;
  refining.update(coarse, options, refinement);
  EXPECT_LE(refining.refined().scene.vertexCount(), coarse.vertexCount() + 10);
  ASSERT_FALSE(refining.splitsPerRound().empty()) << "the coarse room asks for refinement";
  EXPECT_EQ(refining.solution().elementCount(), refining.refined().scene.vertexCount());

  const std::size_t kept = refining.refined().scene.vertexCount();
  const std::vector<Vec3f> direct = refining.solution().direct;
  refinement.maxVertices = 0;
  int calls = 0;
  EXPECT_THROW(refining.update(coarse, options, refinement,
                 [&](const char*, double) { return ++calls < 20; }),
    Aborted);
  EXPECT_EQ(refining.refined().scene.vertexCount(), kept);
  EXPECT_EQ(refining.solution().direct, direct);
}

TEST(Refine, BadSettingsAreNamed)
{
  const Scene coarse = test::roomWithBlock(10.f);
  RefiningSolver refining;
  RefinementOptions r;
  r.tolerance = 0.f;
  EXPECT_NE(errorOf([&] { refining.update(coarse, {}, r); }).find("tolerance"), std::string::npos);
  r.tolerance = std::nanf("");
  EXPECT_NE(errorOf([&] { refining.update(coarse, {}, r); }).find("tolerance"), std::string::npos);
  r = {};
  r.rounds = 0;
  EXPECT_NE(errorOf([&] { refining.update(coarse, {}, r); }).find("rounds"), std::string::npos);
  r = {};
  r.maxVertices = 3;
  EXPECT_NE(errorOf([&] { refining.update(coarse, {}, r); }).find("budget"), std::string::npos);
}

TEST(Refine, ALightMoveKeepsTheRefinedSurfaceAndRelinksNothing)
{
  Scene room = test::roomWithBlock(10.f);
  SolverOptions options;
  options.backend = Backend::Cpu;
  options.raysPerVertex = 64;
  RefiningSolver refining;
  const RefinementOptions refinement;
  refining.update(room, options, refinement);
  ASSERT_FALSE(refining.splitsPerRound().empty()) << "the coarse room asks for refinement";
  const RefinedScene refined = refining.refined();
  const auto stage = [&refining](const std::string& name) {
    for (const StageStats& s : refining.stats().stages)
    {
      if (s.name == name)
      {
        return s;
      }
    }
    return StageStats();
  };
  ASSERT_TRUE(stage("Links").ran);

  room.lights[0].position = room.lights[0].position + Vec3f(0.5f, -0.3f, 0.2f);
  room.albedo[0] = Vec3f(0.2f, 0.3f, 0.4f);
  const Solution& moved = refining.update(room, options, refinement);
  EXPECT_EQ(refining.refined().scene.positions, refined.scene.positions);
  EXPECT_EQ(refining.refined().scene.albedo[0], room.albedo[0]);
  EXPECT_FALSE(stage("Links").ran);
  EXPECT_FALSE(stage("Refine").ran);

  // The same light on the same refined surface, solved from scratch.
  Scene fresh = refined.scene;
  fresh.lights = room.lights;
  fresh.albedo = refining.refined().scene.albedo;
  Solver solver;
  const Solution& expected = solver.update(fresh, options);
  EXPECT_EQ(moved.direct, expected.direct);
  EXPECT_LE(test::relativeError(moved.indirect, expected.indirect), 1e-5f);

  // A moved vertex is a new surface: refined again.
  room.positions[0] = room.positions[0] + Vec3f(0.f, 0.f, 0.01f);
  refining.update(room, options, refinement);
  EXPECT_TRUE(stage("Links").ran);
}
