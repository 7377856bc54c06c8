// Proxies: decimation with OpenMesh, the transfer of a proxy's light to the input,
// and the ProxySolver's caching and direct light on the input.
#include "SceneFixtures.h"

#include "linkgi/Error.h"
#include "shared/Metrics.h"
#include "linkgi/Resolution.h"
#include "resolution/Decimate.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <utility>

using namespace linkgi;
using test::errorOf;

namespace
{
Scene validated(Scene s)
{
  validateScene(s);
  return s;
}

double relativeRms(const std::vector<Vec3f>& a, const std::vector<Vec3f>& reference)
{
  double err = 0.0, ref = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    const Vec3f d = a[i] - reference[i];
    err += dot(d, d);
    ref += dot(reference[i], reference[i]);
  }
  return std::sqrt(err / ref);
}
}

TEST(TestProxy, TransferIsExactWhenTheProxyIsTheMeshItself)
{
  const Scene s = validated(test::roomWithBlock());
  const ProxyTransfer transfer = buildTransfer(s, s);
  std::vector<Vec3f> values(s.vertexCount());
  for (std::size_t v = 0; v < values.size(); ++v)
  {
    values[v] = Vec3f(float(v), float(v % 7) + 0.5f, 1.f / float(v + 1));
  }
  const std::vector<Vec3f> carried = transfer.apply(values);
  ASSERT_EQ(carried.size(), values.size());
  for (std::size_t v = 0; v < values.size(); ++v)
  {
    ASSERT_EQ(carried[v], values[v]) << "vertex " << v;
  }
}

TEST(TestProxy, TransferInterpolatesLinearFieldsExactly)
{
  // A fine grid's vertices lie on a coarse grid of the same square: a field linear in
  // position comes back exactly (up to rounding) wherever it is carried.
  const Scene fine = test::twoSquares(false, 16), coarse = test::twoSquares(false, 4);
  const ProxyTransfer transfer = buildTransfer(fine, coarse);
  std::vector<Vec3f> field(coarse.vertexCount());
  for (std::size_t v = 0; v < field.size(); ++v)
  {
    const Vec3f& p = coarse.positions[v];
    field[v] = Vec3f(2.f * p.x + 1.f, p.y - p.z, 3.f * p.z);
  }
  const std::vector<Vec3f> carried = transfer.apply(field);
  for (std::size_t v = 0; v < fine.vertexCount(); ++v)
  {
    const Vec3f& p = fine.positions[v];
    const Vec3f expected(2.f * p.x + 1.f, p.y - p.z, 3.f * p.z);
    ASSERT_LT(length(carried[v] - expected), 1e-5f) << "vertex " << v;
  }
}

TEST(TestProxy, BadTargetsAreRefusedWithAClearMessage)
{
  if (!proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  const Scene s = validated(test::roomWithBlock());
  const std::string zero = errorOf([&] { decimate(s, 0); });
  EXPECT_NE(zero.find("at least 1"), std::string::npos) << zero;
  const std::string larger = errorOf([&] { decimate(s, s.vertexCount() + 10); });
  EXPECT_NE(larger.find("fewer vertices than the input (" + std::to_string(s.vertexCount()) + ")"), std::string::npos)
    << larger;

  // Through the solver: the previous result stays.
  ProxySolver solver;
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.raysPerVertex = 16;
  const Solution before = solver.update(s, o, s.vertexCount() / 2);
  const std::string same = errorOf([&] { solver.update(s, o, s.vertexCount()); });
  EXPECT_NE(same.find("fewer vertices"), std::string::npos) << same;
  EXPECT_EQ(solver.solution().indirect, before.indirect);
  EXPECT_EQ(solver.decimations(), 1u);
}

TEST(TestProxy, DecimationReachesTheTargetAndKeepsInputVertices)
{
  if (!proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  const Scene s = validated(test::roomWithBlock(0.1f));
  const std::size_t target = s.vertexCount() / 4;
  const ProxyMesh proxy = decimate(s, target);
  EXPECT_LE(proxy.scene.vertexCount(), target + target / 20);
  EXPECT_GT(proxy.scene.vertexCount(), target / 2);
  EXPECT_EQ(proxy.droppedTriangles, 0u);
  ASSERT_EQ(proxy.sourceVertex.size(), proxy.scene.vertexCount());
  for (std::size_t v = 0; v < proxy.scene.vertexCount(); ++v)
  {
    const Index from = proxy.sourceVertex[v];
    ASSERT_EQ(proxy.scene.positions[v], s.positions[from]);
    ASSERT_EQ(proxy.scene.normals[v], s.normals[from]);
    ASSERT_EQ(proxy.scene.albedo[v], s.albedo[from]);
  }
  // The room's box keeps its extent: its corners are boundary vertices of the face grids.
  float lo = 1e30f, hi = -1e30f;
  for (const Vec3f& p : proxy.scene.positions)
  {
    lo = std::min(lo, p.x);
    hi = std::max(hi, p.x);
  }
  EXPECT_EQ(lo, -2.f);
  EXPECT_EQ(hi, 2.f);
}

TEST(TestProxy, ATinyClosedSurfaceDecimatesToOneVertex)
{
  // A tetrahedron to one vertex takes the large decimation's path (the target is far below
  // the input), where every vertex lies on the cut between the halves: nothing to sweep
  // there, and the decimater does what it can (a closed surface keeps at least a triangle).
  if (!proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  Scene s;
  s.positions = { { 1.f, 1.f, 1.f }, { 1.f, -1.f, -1.f }, { -1.f, 1.f, -1.f }, { -1.f, -1.f, 1.f } };
  s.normals = s.positions;
  s.triangles = { { { 0, 1, 2 } }, { { 0, 3, 1 } }, { { 0, 2, 3 } }, { { 1, 3, 2 } } };
  s.albedo.assign(4, Vec3f(0.5f));
  s = validated(s);
  const ProxyMesh proxy = decimate(s, 1);
  EXPECT_GE(proxy.scene.vertexCount(), 1u);
  EXPECT_LE(proxy.scene.vertexCount(), 4u);
  for (std::size_t v = 0; v < proxy.scene.vertexCount(); ++v)
  {
    EXPECT_EQ(proxy.scene.positions[v], s.positions[proxy.sourceVertex[v]]);
  }
}

TEST(TestProxy, ALightMoveDoesNotDecimateAgainAndDirectLightIsTheInputs)
{
  if (!proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  Scene s = test::roomWithBlock(0.1f);
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.raysPerVertex = 64;
  ProxySolver proxy;
  Solver full;
  proxy.update(s, o, s.vertexCount() / 3);
  full.update(s, o);
  EXPECT_EQ(proxy.decimations(), 1u);
  EXPECT_TRUE(proxy.stats().stage("Decimate") != nullptr);
  // Direct light on the input: the full solve's own, bit for bit.
  EXPECT_EQ(proxy.solution().direct, full.solution().direct);
  const double rmse = relativeRms(proxy.solution().indirect, full.solution().indirect);
  std::cout << "proxy of " << proxy.proxy().scene.vertexCount() << " / " << s.vertexCount()
            << " vertices: indirect relative RMSE " << rmse << "\n";
  EXPECT_LT(rmse, 0.15); // 0.041 here (64 rays, a third of the vertices)

  s.lights[0].position.x -= 0.7f;
  proxy.update(s, o, s.vertexCount() / 3);
  full.update(s, o);
  EXPECT_EQ(proxy.decimations(), 1u);
  EXPECT_TRUE(proxy.stats().stage("Decimate") == nullptr);
  EXPECT_FALSE(proxy.stats().ran("Links"));
  EXPECT_EQ(proxy.solution().direct, full.solution().direct);
}

TEST(TestProxy, AProxyThatCannotReachItsTargetSaysSo)
{
  if (!proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  // The room's face grids keep their boundary vertices: 20 vertices cannot be reached.
  const Scene s = test::roomWithBlock();
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.raysPerVertex = 16;
  ProxySolver solver;
  solver.update(s, o, 20);
  EXPECT_GT(solver.proxy().scene.vertexCount(), 22u);
  bool warned = false;
  for (const std::string& w : solver.stats().warnings)
  {
    warned = warned || w.find("more than the 20 asked for") != std::string::npos;
  }
  EXPECT_TRUE(warned);
}

TEST(TestProxy, DecimationReportsProgressAndAbortsKeepingThePreviousProxy)
{
  if (!proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  const Scene s = validated(test::roomWithBlock(0.1f));
  const std::size_t target = s.vertexCount() / 4;
  std::vector<double> fractions;
  decimate(s, target, 60.f,
    [&](const char* stage, double f)
    {
      EXPECT_STREQ(stage, "Decimate");
      fractions.push_back(f);
      return true;
    });
  ASSERT_GE(fractions.size(), 10u) << "about a hundred reports";
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  EXPECT_GE(fractions.front(), 0.0);
  EXPECT_LE(fractions.back(), 1.0);

  int calls = 0;
  const auto stopEarly = [&](const char*, double) { return ++calls < 5; };
  EXPECT_THROW(decimate(s, target, 60.f, stopEarly), Aborted);
  EXPECT_EQ(calls, 5) << "the decimation stops at the first refusal";

  // Through the solver: an abort during a new decimation keeps the last proxy and result.
  ProxySolver solver;
  SolverOptions o;
  o.backend = Backend::Cpu;
  o.raysPerVertex = 16;
  const Solution before = solver.update(s, o, target);
  calls = 0;
  EXPECT_THROW(solver.update(s, o, target / 2, stopEarly), Aborted);
  EXPECT_EQ(solver.decimations(), 1u);
  EXPECT_EQ(solver.solution().indirect, before.indirect);
}

namespace
{
/// The squared distance from p to triangle abc, computed another way than the transfer
/// does: the plane's foot where it lies inside, else the nearest of the three edges.
float squaredDistanceToTriangle(const Vec3f& p, const Vec3f& a, const Vec3f& b, const Vec3f& c)
{
  const Vec3f n = cross(b - a, c - a);
  const float nn = dot(n, n);
  if (nn > 0.f)
  {
    const Vec3f foot = p - n * (dot(p - a, n) / nn);
    const float u = dot(cross(c - b, foot - b), n), v = dot(cross(a - c, foot - c), n), w = dot(cross(b - a, foot - a), n);
    if (u >= 0.f && v >= 0.f && w >= 0.f)
    {
      return dot(p - foot, p - foot);
    }
  }
  float best = std::numeric_limits<float>::max();
  for (const auto& [e0, e1] : { std::pair{ a, b }, std::pair{ b, c }, std::pair{ c, a } })
  {
    const Vec3f d = e1 - e0;
    const float t = std::clamp(dot(p - e0, d) / std::max(dot(d, d), 1e-30f), 0.f, 1.f);
    const Vec3f q = e0 + d * t;
    best = std::min(best, dot(p - q, p - q));
  }
  return best;
}
}

// A decimation to a tenth collapses the short edges first (without priorities) and leaves
// the last collapses to the Decimater: the proxy still has the target's size, is made of
// input vertices, and no triangle turns more than the normal deviation (60 degrees) from the
// input normals at its corners, nor is a sliver. The sweep runs in two halves at once; where
// they meet, every edge still has at most one triangle on each side (no triangle refused,
// none twice).
TEST(TestProxy, ALargeDecimationReachesItsTargetWithoutTurningTriangles)
{
  if (!proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  const Scene s = validated(makeStandardScene("torso"));
  const std::size_t target = s.vertexCount() / 10;
  int reports = 0;
  const ProxyMesh proxy = decimate(s, target, 60.f, [&](const char*, double) { return ++reports > 0; });
  EXPECT_GT(reports, 0);
  EXPECT_LE(proxy.scene.vertexCount(), target + target / 20);
  EXPECT_GT(proxy.scene.vertexCount(), target / 2);
  for (std::size_t v = 0; v < proxy.scene.vertexCount(); ++v)
  {
    ASSERT_EQ(proxy.scene.positions[v], s.positions[proxy.sourceVertex[v]]);
  }
  // Slivers (a normal that is rounding noise) only where the input had them.
  const auto slivers = [](const Scene& m) {
    std::size_t count = 0;
    for (const Triangle& t : m.triangles)
    {
      const Vec3f &a = m.positions[t.v[0]], &b = m.positions[t.v[1]], &c = m.positions[t.v[2]];
      const float longest2 = std::max({ dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c) });
      count += !(length(cross(b - a, c - a)) > 2e-3f * longest2);
    }
    return count;
  };
  EXPECT_LE(slivers(proxy.scene), slivers(s));
  EXPECT_EQ(proxy.droppedTriangles, 0u);
  std::vector<std::pair<Index, Index>> directed;
  for (const Triangle& t : proxy.scene.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      directed.emplace_back(t.v[k], t.v[(k + 1) % 3]);
    }
  }
  std::sort(directed.begin(), directed.end());
  EXPECT_EQ(std::adjacent_find(directed.begin(), directed.end()), directed.end())
    << "an edge with two triangles on the same side";
  std::size_t turned = 0;
  for (const Triangle& t : proxy.scene.triangles)
  {
    const Vec3f& a = proxy.scene.positions[t.v[0]];
    const Vec3f n = cross(proxy.scene.positions[t.v[1]] - a, proxy.scene.positions[t.v[2]] - a);
    for (Index v : t.v)
    {
      turned += dot(n, s.normals[proxy.sourceVertex[v]]) < 0.5f * length(n); // over 60 degrees
    }
  }
  EXPECT_EQ(turned, 0u) << "corners whose input normal turns more than 60 degrees from their proxy triangle";
}

// The transfer finds each input vertex's nearest proxy triangle facing its way: the
// distance to the triangle and point it chose equals a brute-force search's.
TEST(TestProxy, TransferFindsTheNearestFacingTriangle)
{
  if (!proxyAvailable())
  {
    GTEST_SKIP() << "This build has no OpenMesh.";
  }
  const Scene s = validated(makeStandardScene("torso"));
  const Scene p = decimate(s, s.vertexCount() / 10).scene;
  const ProxyTransfer transfer = buildTransfer(s, p);
  std::size_t worse = 0;
  for (std::size_t v = 0; v < s.vertexCount(); ++v)
  {
    float best = std::numeric_limits<float>::max();
    for (const Triangle& t : p.triangles)
    {
      const Vec3f &a = p.positions[t.v[0]], &b = p.positions[t.v[1]], &c = p.positions[t.v[2]];
      if (dot(cross(b - a, c - a), s.normals[v]) > 0.f)
      {
        best = std::min(best, squaredDistanceToTriangle(s.positions[v], a, b, c));
      }
    }
    const Triangle& t = transfer.corners[v];
    const auto& w = transfer.weights[v];
    const Vec3f q = p.positions[t.v[0]] * w[0] + p.positions[t.v[1]] * w[1] + p.positions[t.v[2]] * w[2];
    const float chosen = dot(q - s.positions[v], q - s.positions[v]);
    worse += std::sqrt(chosen) > std::sqrt(best) * 1.0001f + 1e-6f;
  }
  EXPECT_EQ(worse, 0u) << "input vertices whose proxy point is farther than the nearest facing triangle";
}
