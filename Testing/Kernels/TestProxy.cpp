// Proxies (issue 15): decimation with OpenMesh, the transfer of a proxy's light to the input,
// and the ProxySolver's caching and direct light on the input.
#include "SceneFixtures.h"

#include "linkgi/Error.h"
#include "linkgi/Metrics.h"
#include "linkgi/Proxy.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>

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
