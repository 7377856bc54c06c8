// Inputs that fuzzing (Testing/Fuzz) found to break the engine, kept as regression tests.
#include "linkgi/Scene.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace linkgi;

namespace
{
/// One triangle in z = 0 and a fourth vertex that no triangle uses.
Scene triangleAndLoneVertex(const Vec3f& firstNormal, const Vec3f& loneNormal)
{
  Scene s;
  s.positions = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 5, 5, 5 } };
  s.normals = { firstNormal, { 0, 0, 1 }, { 0, 0, 1 }, loneNormal };
  s.albedo.assign(4, Vec3f(0.5f));
  s.triangles = { { { 0, 1, 2 } } };
  return s;
}
}

TEST(FuzzFindings, NormalsOfAnyFiniteLengthBecomeUnitNormals)
{
  // The squares of (1e20, 0, 0) overflowed to a length of infinity, and the normal divided
  // by it became (0, 0, 0); those of (1e-30, 0, 0) underflowed to 0, and the normal was
  // replaced by the face normal although it had a direction of its own.
  for (const float size : { 1e20f, 3e38f, -3e38f, 1e-30f, 1e-45f, 2.f })
  {
    SCOPED_TRACE(size);
    Scene s = triangleAndLoneVertex(Vec3f(size, 0.f, 0.f), Vec3f(0.f, 0.f, 1.f));
    validateScene(s);
    EXPECT_EQ(s.normals[0].x, size > 0.f ? 1.f : -1.f);
    EXPECT_EQ(s.normals[0].y, 0.f);
    EXPECT_EQ(s.normals[0].z, 0.f);
  }
}

TEST(FuzzFindings, AZeroNormalOfAVertexOfNoTriangleBecomesAUnitNormal)
{
  // A zero normal is replaced by the sum of the adjacent faces' normals; a vertex of no
  // triangle has none, and kept its zero normal.
  Scene s = triangleAndLoneVertex(Vec3f(0.f, 0.f, 1.f), Vec3f(0.f));
  const std::vector<std::string> warnings = validateScene(s);
  EXPECT_NEAR(length(s.normals[3]), 1.f, 1e-6f);
  EXPECT_FALSE(warnings.empty()); // the replacement is reported
}
