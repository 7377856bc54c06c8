#include "SceneFixtures.h"

#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

using namespace linkgi;

namespace
{
SolverOptions fastOptions()
{
  SolverOptions o;
  o.raysPerVertex = 64;
  return o;
}

void expectSameSolution(const Solution& a, const Solution& b)
{
  ASSERT_EQ(a.elementCount(), b.elementCount());
  for (std::size_t i = 0; i < a.elementCount(); ++i)
  {
    ASSERT_EQ(a.direct[i], b.direct[i]) << i;
    ASSERT_EQ(a.indirect[i], b.indirect[i]) << i;
    ASSERT_EQ(a.radiance[i], b.radiance[i]) << i;
  }
}

Solution freshSolve(const Scene& s, const SolverOptions& o)
{
  Solver solver;
  return solver.update(s, o);
}
}

TEST(TestSolverCache, LightOnlyChangeRebuildsNoLinks)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, fastOptions());
  ASSERT_EQ(solver.stats().runs("LinkBuilds"), 1u);
  s.lights[0].position = { -0.7f, 2.2f, 0.1f };
  s.lights[0].intensity = { 3.f, 5.f, 9.f };
  const Solution& moved = solver.update(s, fastOptions());
  EXPECT_EQ(solver.stats().runs("LinkBuilds"), 1u);
  EXPECT_EQ(solver.stats().bvhBuilds, 1u);
  EXPECT_FALSE(solver.stats().ran("Links"));
  EXPECT_TRUE(solver.stats().ran("LightLinks"));
  // Bit-identical to solving the moved-light scene from scratch.
  expectSameSolution(moved, freshSolve(s, fastOptions()));
}

TEST(TestSolverCache, MaterialChangeOnlyRebounces)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, fastOptions());
  for (Vec3f& a : s.albedo)
  {
    a = a * 0.5f;
  }
  s.environment.color = Vec3f(0.1f);
  const Solution& changed = solver.update(s, fastOptions());
  EXPECT_FALSE(solver.stats().ran("Links"));
  EXPECT_FALSE(solver.stats().ran("LightLinks"));
  EXPECT_TRUE(solver.stats().ran("Bounces"));
  expectSameSolution(changed, freshSolve(s, fastOptions()));
}

TEST(TestSolverCache, MovedVerticesRefitAndRelink)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, fastOptions());
  for (Vec3f& p : s.positions)
  {
    p.y *= 1.1f; // stretch the room and block; normals stay valid
  }
  const Solution& refit = solver.update(s, fastOptions());
  EXPECT_TRUE(solver.stats().refitBvh);
  EXPECT_FALSE(solver.stats().builtBvh);
  EXPECT_TRUE(solver.stats().ran("Links"));
  // A refit BVH finds the same closest hits as a fresh build.
  expectSameSolution(refit, freshSolve(s, fastOptions()));
}

TEST(TestSolverCache, TopologyChangeRebuildsAndNoChangeDoesNothing)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  solver.update(s, fastOptions());
  solver.update(s, fastOptions());
  EXPECT_FALSE(solver.stats().ran("Bounces"));
  EXPECT_EQ(solver.stats().runs("BounceRuns"), 1u);
  s.triangles.pop_back();
  solver.update(s, fastOptions());
  EXPECT_TRUE(solver.stats().builtBvh);
  EXPECT_EQ(solver.stats().bvhBuilds, 2u);
}

TEST(TestSolverCache, AbortKeepsThePreviousSolution)
{
  Scene s = test::roomWithBlock();
  Solver solver;
  const Solution before = solver.update(s, fastOptions());
  for (Vec3f& p : s.positions)
  {
    p.x *= 0.9f;
  }
  for (double stopAt : { 0.1, 0.8, 0.9, 0.97 }) // inside links, compression, light links, bounces
  {
    int calls = 0;
    double last = -1.0;
    const auto progress = [&](const char*, double f) {
      EXPECT_GE(f, last); // monotone
      last = f;
      ++calls;
      return f < stopAt;
    };
    EXPECT_THROW(solver.update(s, fastOptions(), progress), Aborted);
    EXPECT_GT(calls, 1);
    expectSameSolution(solver.solution(), before);
  }
  // The solver still works, and matches a fresh solve.
  expectSameSolution(solver.update(s, fastOptions()), freshSolve(s, fastOptions()));
}

TEST(TestSolverCache, TwoSidedElementsAppendBackSides)
{
  Scene s = test::roomWithBlock();
  SolverOptions o = fastOptions();
  o.twoSided = true;
  Solver solver;
  const Solution& sol = solver.update(s, o);
  ASSERT_EQ(sol.elementCount(), 2 * s.vertexCount());
  // Inside a closed room the backs of the walls see only the outside of the other walls'
  // backs and the black sky: no light reaches them.
  double back = 0.0, front = 0.0;
  for (std::size_t v = 0; v < s.vertexCount(); ++v)
  {
    front += luminance(sol.direct[v] + sol.indirect[v]);
    back += luminance(sol.direct[v + s.vertexCount()]);
  }
  EXPECT_GT(front, 0.0);
  // The block's backs face inward (inside the block): dark as well.
  EXPECT_EQ(back, 0.0);
}
