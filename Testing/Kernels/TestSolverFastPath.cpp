// Light and material updates on unchanged geometry borrow the cached, validated arrays
// instead of copying and re-validating them: the checks and repairs of the changed arrays
// must still happen, and an error must leave the cache whole.
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
