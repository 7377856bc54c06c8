#include "SceneFixtures.h"

#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <limits>

using namespace linkgi;
using test::quickOptions;

namespace
{
/// Expects update() to throw linkgi::Error whose message contains `words`.
void expectError(const Scene& s, const std::string& words, SolverOptions o = quickOptions())
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
  const Solution clean = Solver().update(s, quickOptions());
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
  const Solution& sol = solver.update(s, quickOptions());
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
  const Solution& sol = solver.update(s, quickOptions());
  for (std::size_t i = 0; i < sol.elementCount(); ++i)
  {
    EXPECT_EQ(sol.direct[i], Vec3f(0.f));
    EXPECT_NEAR(sol.indirect[i].x, kPi * 0.5f, 1e-4f);
  }
  EXPECT_TRUE(solver.stats().warnings.empty());
  // Nothing at all: zeros and a warning, no error.
  s.environment.color = Vec3f(0.f);
  const Solution& dark = solver.update(s, quickOptions());
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
  const Solution sol = solver.update(s, quickOptions());
  EXPECT_NE(solver.stats().warnings.at(0).find("Clamped the albedo"), std::string::npos);
  const Solution ref = Solver().update(clamped, quickOptions());
  for (std::size_t i = 0; i < sol.elementCount(); ++i)
  {
    ASSERT_EQ(sol.radiance[i], ref.radiance[i]);
  }
  SolverOptions reject = quickOptions();
  reject.albedoPolicy = AlbedoPolicy::Reject;
  expectError(s, "albedo above 1", reject);
}

TEST(TestBadInput, ErrorKeepsThePreviousSolution)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  const Solution before = solver.update(s, quickOptions());
  s.positions[0].x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(solver.update(s, quickOptions()), Error);
  ASSERT_EQ(solver.solution().elementCount(), before.elementCount());
  for (std::size_t i = 0; i < before.elementCount(); ++i)
  {
    ASSERT_EQ(solver.solution().radiance[i], before.radiance[i]);
  }
}

namespace
{
/// A sphere over a floor under the sky and a slanted sun: direct, bounced and sky light.
Scene sphereOverFloor()
{
  MeshBuilder b;
  b.addQuadGrid({ -2, 0, 2 }, { 4, 0, 0 }, { 0, 0, -4 }, 12, 12, Vec3f(0.6f, 0.6f, 0.6f));
  b.addIcosphere({ 0, 0.8f, 0 }, 0.6f, 2, Vec3f(0.8f, 0.3f, 0.2f));
  Scene s = b.take();
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3f(0.4f, -1.f, 0.2f));
  sun.intensity = { 2.f, 2.f, 2.f };
  s.lights.push_back(sun);
  s.environment.color = { 0.2f, 0.3f, 0.5f };
  return s;
}
}

TEST(TestBadInput, SceneSizeDoesNotMatter)
{
  // A mesh of size 1e30 used to lose most triangles as "degenerate" (the area test
  // overflowed) and one of size 1e-30 all of them; rays and 1/r^2 overflow or underflow in
  // single precision long before that. The solver rescales by a power of two internally.
  const Scene unit = sphereOverFloor();
  SolverOptions o = quickOptions();
  o.backend = Backend::Cpu;
  const Solution reference = Solver().update(unit, o);
  for (const float scale : { 1e30f, 1e-30f, 1e12f })
  {
    Scene s = unit;
    for (Vec3f& p : s.positions)
    {
      p = p * scale;
    }
    Solver solver;
    const Solution& sol = solver.update(s, o);
    EXPECT_TRUE(solver.stats().warnings.empty()) << scale << ": " << solver.stats().warnings.at(0);
    ASSERT_EQ(sol.elementCount(), reference.elementCount());
    double sumRef = 0.0, sumSol = 0.0;
    for (std::size_t e = 0; e < sol.elementCount(); ++e)
    {
      ASSERT_TRUE(isFinite(sol.radiance[e]));
      EXPECT_NEAR(sol.direct[e].y, reference.direct[e].y, 1e-3f * (1.f + reference.direct[e].y));
      sumRef += reference.indirect[e].y;
      sumSol += sol.indirect[e].y;
    }
    EXPECT_NEAR(sumSol, sumRef, 1e-3 * sumRef) << "scale " << scale;
    // A light-only update on the rescaled geometry (the lent arrays) scales the lights alike.
    s.lights[0].intensity = { 1.f, 1.f, 1.f };
    const Solution& half = solver.update(s, o);
    EXPECT_FALSE(solver.stats().ran("Links"));
    EXPECT_NEAR(half.direct[5].y, 0.5f * reference.direct[5].y, 1e-3f * (1.f + reference.direct[5].y));
  }
}

TEST(TestBadInput, PointLightsFollowTheRescaledGeometry)
{
  // A point light's irradiance I cos / r^2 at scale 1e12: I and r^2 grow by 1e24 together.
  Scene unit = sphereOverFloor();
  unit.lights[0].type = LightType::Point;
  unit.lights[0].position = { 0.5f, 3.f, 0.2f };
  SolverOptions o = quickOptions();
  o.backend = Backend::Cpu;
  const Solution reference = Solver().update(unit, o);
  Scene big = unit;
  for (Vec3f& p : big.positions)
  {
    p = p * 1e12f;
  }
  big.lights[0].position = big.lights[0].position * 1e12f;
  big.lights[0].intensity = big.lights[0].intensity * 1e24f;
  const Solution sol = Solver().update(big, o);
  for (std::size_t e = 0; e < sol.elementCount(); e += 3)
  {
    EXPECT_NEAR(sol.direct[e].x, reference.direct[e].x, 1e-3f * (1.f + reference.direct[e].x));
  }
  // A light too bright for a scene this small is an error, not an infinity.
  Scene tiny = unit;
  for (Vec3f& p : tiny.positions)
  {
    p = p * 1e-30f;
  }
  tiny.lights[0].position = tiny.lights[0].position * 1e-30f;
  expectError(tiny, "exceeds single precision", o);
}
