// Inputs that fuzzing (Testing/Fuzz) found to break the engine, kept as regression tests.
#include "linkgi/Error.h"
#include "linkgi/Scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

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

TEST(FuzzFindings, ALightFarFromATinySceneKeepsFinitePositionsOrIsAnError)
{
  // A mesh 1e-16 across is rescaled by 2^54; a light position of 1.8e28 became infinite.
  // A directional light has no position to scale; a point light that far is an error
  // naming it.
  Scene s = triangleAndLoneVertex(Vec3f(0.f, 0.f, 1.f), Vec3f(0.f, 0.f, 1.f));
  for (Vec3f& p : s.positions)
  {
    p = p * 1e-16f;
  }
  Light sun;
  sun.type = LightType::Directional;
  sun.position = Vec3f(1.8e28f);
  s.lights = { sun };
  Scene valid = s;
  validateScene(valid);
  EXPECT_NE(valid.lengthExponent, 0);
  EXPECT_TRUE(std::isfinite(valid.lights[0].position.x));

  Light bulb;
  bulb.position = Vec3f(1.8e28f);
  s.lights = { bulb };
  try
  {
    validateScene(s);
    ADD_FAILURE() << "a point light at infinity in the scene's scale was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("Light 0 is so far"), std::string::npos) << e.what();
  }
}

TEST(FuzzFindings, LightDirectionsOfAnyFiniteLengthBecomeUnitDirections)
{
  // normalize() of (0, 0, -1e20) at use divided by an infinite length: no light at all; a
  // direction of (0, 0, -1e-30) was refused as "without a direction".
  for (const float size : { 1e20f, 1e-30f, 1.f })
  {
    SCOPED_TRACE(size);
    Scene s = triangleAndLoneVertex(Vec3f(0.f, 0.f, 1.f), Vec3f(0.f, 0.f, 1.f));
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = Vec3f(0.f, 0.f, -size);
    s.lights = { sun };
    validateScene(s);
    EXPECT_EQ(s.lights[0].direction.z, -1.f);
  }
}

TEST(FuzzFindings, ANegativeEnvironmentIsAnError)
{
  // A negative environment colour or texel was accepted and lit the scene negatively.
  const auto message = [](const Environment& sky) {
    Scene s = triangleAndLoneVertex(Vec3f(0.f, 0.f, 1.f), Vec3f(0.f, 0.f, 1.f));
    s.environment = sky;
    try
    {
      validateScene(s);
    }
    catch (const Error& e)
    {
      return std::string(e.what());
    }
    return std::string();
  };
  Environment negative;
  negative.color = Vec3f(0.f, -1e22f, 0.f);
  EXPECT_NE(message(negative).find("environment colour"), std::string::npos);

  Environment texel;
  texel.color = Vec3f(1.f);
  texel.width = 2;
  texel.height = 1;
  texel.texels = { Vec3f(1.f), Vec3f(-1.f, 0.f, 0.f) };
  EXPECT_NE(message(texel).find("Texel 1 of the environment map"), std::string::npos);

  Environment size = texel;
  size.width = -2;
  size.height = -1;
  EXPECT_NE(message(size).find("width x height"), std::string::npos);
}

TEST(FuzzFindings, EmissionBeyondWhatTheBouncesCanCarryIsAnError)
{
  // An emission of 3.4e38, finite, was accepted; gathered over the bounces it gave
  // infinite radiance. Above 1e30 it is an error naming the vertex.
  Scene s = triangleAndLoneVertex(Vec3f(0.f, 0.f, 1.f), Vec3f(0.f, 0.f, 1.f));
  s.emission.assign(4, Vec3f(0.f));
  s.emission[2] = Vec3f(3.4e38f);
  try
  {
    validateScene(s);
    ADD_FAILURE() << "an emission of 3.4e38 was accepted";
  }
  catch (const Error& e)
  {
    EXPECT_NE(std::string(e.what()).find("Vertex 2 has a negative, non-finite or too large"),
      std::string::npos) << e.what();
  }
  s.emission[2] = Vec3f(1e30f);
  EXPECT_NO_THROW(validateScene(s));
}
