// Updates borrow the cached, validated arrays that did not change instead of copying and
// re-validating them (a light or material update every array of the mesh, a deformation all
// but the positions): the checks and repairs of the changed arrays must still happen, and
// an error must leave the cache whole.
#include "SceneFixtures.h"

#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace linkgi;
using test::quickOptions;

namespace
{
void expectSame(const Solution& a, const Solution& b)
{
  ASSERT_EQ(a.elementCount(), b.elementCount());
  for (std::size_t i = 0; i < a.elementCount(); ++i)
  {
    ASSERT_EQ(a.radiance[i], b.radiance[i]) << i;
    ASSERT_EQ(a.indirect[i], b.indirect[i]) << i;
  }
}
}

TEST(SolverFastPath, AlbedoAboveOneIsStillClampedWithAWarning)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, quickOptions());
  s.albedo[3] = Vec3f(1.5f, 0.2f, 0.2f);
  const Solution& clamped = solver.update(s, quickOptions());
  ASSERT_EQ(solver.stats().warnings.size(), 1u);
  EXPECT_NE(solver.stats().warnings[0].find("Clamped the albedo of 1 vertices"), std::string::npos);
  Solver fresh;
  expectSame(clamped, fresh.update(s, quickOptions()));
}

TEST(SolverFastPath, BadLightOrAlbedoIsAnErrorThatKeepsTheCache)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  const Solution before = solver.update(s, quickOptions());
  Scene badLight = s;
  badLight.lights[0].intensity.x = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(solver.update(badLight, quickOptions()), Error);
  Scene badAlbedo = s;
  badAlbedo.albedo[7].y = -0.5f;
  EXPECT_THROW(solver.update(badAlbedo, quickOptions()), Error);
  expectSame(solver.solution(), before);
  // The borrowed arrays went back to the cache: a light change still relinks nothing and
  // gives a fresh solve's answer.
  s.lights[0].position = { -0.5f, 2.4f, 0.3f };
  const Solution& moved = solver.update(s, quickOptions());
  EXPECT_FALSE(solver.stats().ran("Links"));
  EXPECT_EQ(solver.stats().bvhBuilds, 1u);
  Solver fresh;
  expectSame(moved, fresh.update(s, quickOptions()));
}

TEST(SolverFastPath, DeformationThatFlattensATriangleRemovesIt)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, quickOptions());
  // Move one vertex onto another of its triangle: the lent triangles cannot be repaired in
  // place, so the update validates a copy of them, which drops that triangle and its kind.
  Scene flat = s;
  const Triangle t = flat.triangles[5];
  flat.positions[t.v[1]] = flat.positions[t.v[0]];
  const Solution& moved = solver.update(flat, quickOptions());
  ASSERT_FALSE(solver.stats().warnings.empty());
  EXPECT_NE(solver.stats().warnings[0].find("degenerate triangles"), std::string::npos);
  EXPECT_TRUE(solver.stats().builtBvh); // a topology change
  Solver fresh;
  expectSame(moved, fresh.update(flat, quickOptions()));
  // And back: the cache held the shortened triangle list, the input the full one.
  const Solution& back = solver.update(s, quickOptions());
  EXPECT_TRUE(solver.stats().builtBvh);
  Solver again;
  expectSame(back, again.update(s, quickOptions()));
}

TEST(SolverFastPath, BadPositionIsAnErrorThatKeepsTheCache)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  const Solution before = solver.update(s, quickOptions());
  Scene bad = s;
  for (Vec3f& p : bad.positions)
  {
    p.y *= 1.05f;
  }
  bad.positions[11].z = std::numeric_limits<float>::infinity();
  EXPECT_NE(test::errorOf([&] { solver.update(bad, quickOptions()); }).find("Vertex 11"), std::string::npos);
  expectSame(solver.solution(), before);
  // The lent normals and triangles went back: a light change relinks nothing.
  s.lights[0].position = { -0.5f, 2.4f, 0.3f };
  const Solution& moved = solver.update(s, quickOptions());
  EXPECT_FALSE(solver.stats().ran("Links"));
  Solver fresh;
  expectSame(moved, fresh.update(s, quickOptions()));
}

TEST(SolverFastPath, MaterialChangeWithTheSameAlbedoIsAChange)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, quickOptions());
  s.triangleMaterials.assign(s.triangleCount(), MaterialType::Diffuse);
  s.triangleMaterials[3] = MaterialType::Mirror;
  solver.update(s, quickOptions());
  EXPECT_TRUE(solver.stats().ran("Bounces"));
  EXPECT_FALSE(solver.stats().ran("Links"));
}
