#include "SceneFixtures.h"

#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <limits>

using namespace linkgi;

namespace
{
SolverOptions fast()
{
  SolverOptions o;
  o.raysPerVertex = 16;
  return o;
}

/// Expects update() to throw linkgi::Error whose message contains `words`.
void expectError(const Scene& s, const std::string& words, SolverOptions o = fast())
{
  Solver solver;
  try
  {
    solver.update(s, o);
    ADD_FAILURE() << "no error for: " << words;
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}
}

TEST(TestBadInput, EmptySceneAndNoTriangles)
{
  expectError(Scene{}, "no vertices");
  Scene s = test::roomWithBlock();
  s.triangles.clear();
  expectError(s, "no triangles");
}

TEST(TestBadInput, NonFiniteData)
{
  const Scene good = test::roomWithBlock();
  Scene s = good;
  s.positions[5].y = std::numeric_limits<float>::quiet_NaN();
  expectError(s, "Vertex 5 has a non-finite (NaN or Inf) position");
  s = good;
  s.normals[2].x = std::numeric_limits<float>::infinity();
  expectError(s, "normal");
  s = good;
  s.lights[0].intensity.x = std::numeric_limits<float>::infinity();
  expectError(s, "Light 0");
  s = good;
  s.albedo[1] = Vec3f(-0.1f);
  expectError(s, "negative");
}

TEST(TestBadInput, BadIndicesAndSizes)
{
  Scene s = test::roomWithBlock();
  s.triangles[0].v[1] = Index(s.vertexCount());
  expectError(s, "refers to vertex");
  s = test::roomWithBlock();
  s.albedo.pop_back();
  expectError(s, "one value per vertex");
  SolverOptions rays200;
  rays200.raysPerVertex = 200;
  expectError(test::roomWithBlock(), "perfect square", rays200);
}

TEST(TestBadInput, DegenerateTrianglesAreRemoved)
{
  Scene s = test::roomWithBlock();
  const Solution clean = Solver().update(s, fast());
  s.triangles.push_back({ { 0, 0, 1 } });                 // repeated index
  s.positions.push_back(s.positions[3]);                  // zero-area sliver
  s.normals.push_back(s.normals[3]);
  s.albedo.push_back(s.albedo[3]);
  if (!s.emission.empty())
  {
    s.emission.push_back(s.emission[3]);
  }
  s.triangles.push_back({ { 3, Index(s.vertexCount() - 1), 4 } });
  Solver solver;
  const Solution& sol = solver.update(s, fast());
  ASSERT_EQ(solver.stats().warnings.size(), 1u);
  EXPECT_NE(solver.stats().warnings[0].find("2 degenerate"), std::string::npos);
  for (const Vec3f& r : sol.radiance)
  {
    EXPECT_TRUE(isFinite(r));
  }
  EXPECT_EQ(sol.elementCount(), clean.elementCount() + 1);
  Scene allBad;
  allBad.positions = { { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 } };
  allBad.normals.assign(3, { 0, 0, 1 });
  allBad.albedo.assign(3, Vec3f(0.5f));
  allBad.triangles = { { { 0, 1, 2 } } };
  expectError(allBad, "degenerate");
}

TEST(TestBadInput, ZeroLights)
{
  // Environment only: an upward plane under a constant sky of radiance 0.5 receives
  // E = pi * 0.5 everywhere (every ray misses), no direct light.
  MeshBuilder b;
  b.addQuadGrid({ 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, 4, 4, Vec3f(0.5f));
  Scene s = b.take();
  s.environment.color = Vec3f(0.5f);
  Solver solver;
  const Solution& sol = solver.update(s, fast());
  for (std::size_t i = 0; i < sol.elementCount(); ++i)
  {
    EXPECT_EQ(sol.direct[i], Vec3f(0.f));
    EXPECT_NEAR(sol.indirect[i].x, kPi * 0.5f, 1e-4f);
  }
  EXPECT_TRUE(solver.stats().warnings.empty());
  // Nothing at all: zeros and a warning, no error.
  s.environment.color = Vec3f(0.f);
  const Solution& dark = solver.update(s, fast());
  for (const Vec3f& r : dark.radiance)
  {
    EXPECT_EQ(r, Vec3f(0.f));
  }
  ASSERT_EQ(solver.stats().warnings.size(), 1u);
  EXPECT_NE(solver.stats().warnings[0].find("no lights"), std::string::npos);
}

TEST(TestBadInput, AlbedoAboveOneIsClampedOrRejected)
{
  Scene s = test::roomWithBlock();
  Scene clamped = s;
  for (std::size_t i = 0; i < s.vertexCount(); i += 2)
  {
    s.albedo[i] = Vec3f(1.5f, 0.5f, 2.f);
    clamped.albedo[i] = Vec3f(1.f, 0.5f, 1.f);
  }
  Solver solver;
  const Solution sol = solver.update(s, fast());
  EXPECT_NE(solver.stats().warnings.at(0).find("Clamped the albedo"), std::string::npos);
  const Solution ref = Solver().update(clamped, fast());
  for (std::size_t i = 0; i < sol.elementCount(); ++i)
  {
    ASSERT_EQ(sol.radiance[i], ref.radiance[i]);
  }
  SolverOptions reject = fast();
  reject.albedoPolicy = AlbedoPolicy::Reject;
  expectError(s, "albedo above 1", reject);
}

TEST(TestBadInput, ErrorKeepsThePreviousSolution)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  const Solution before = solver.update(s, fast());
  s.positions[0].x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(solver.update(s, fast()), Error);
  ASSERT_EQ(solver.solution().elementCount(), before.elementCount());
  for (std::size_t i = 0; i < before.elementCount(); ++i)
  {
    ASSERT_EQ(solver.solution().radiance[i], before.radiance[i]);
  }
}
