// A point or spot light at (or almost at) a vertex: the irradiance intensity / r^2 grows
// without bound, and in single precision it overflowed to infinity for a light within
// about 1e-19 of a vertex (the likely cause of the two "deadly signal" reports of the long
// SolverOptions fuzz run). unshadowedIrradiance (CPU, CUDA and the reference)
// bounds r from below and the result from above, so the solution stays finite.
#include "shared/DirectLight.h"
#include "linkgi/Error.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace linkgi;

namespace
{
/// A unit square in z = 0 facing +z, with a point light `offset` above its first corner.
Scene squareWithLightAt(const Vec3f& offset, float intensity)
{
  Scene s;
  s.positions = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  s.normals.assign(4, Vec3f(0, 0, 1));
  s.albedo.assign(4, Vec3f(0.5f));
  s.triangles = { { { 0, 1, 2 } }, { { 0, 2, 3 } } };
  Light l;
  l.position = offset;
  l.intensity = Vec3f(intensity);
  s.lights.push_back(l);
  return s;
}

bool finite(const Vec3f& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
}

TEST(NearLight, TheIrradianceOfALightAtAVertexIsBounded)
{
  Light l;
  l.intensity = Vec3f(3e38f);
  // Up to 1e-22, r^2 is a normal float or a denormal; beyond, it underflows to 0, which
  // reads as a light at the vertex: nothing (below).
  for (const float d : { 1e-19f, 1e-20f, 1e-22f })
  {
    SCOPED_TRACE(d);
    l.position = Vec3f(0.f, 0.f, d);
    Vec3f toLight;
    const Vec3f e = unshadowedIrradiance(l, Vec3f(0.f), Vec3f(0, 0, 1), toLight);
    EXPECT_EQ(e.x, kMaxLightIrradiance);
  }
  for (const float d : { 0.f, 1e-30f, 1e-45f })
  {
    l.position = Vec3f(0.f, 0.f, d);
    Vec3f toLight;
    EXPECT_EQ(unshadowedIrradiance(l, Vec3f(0.f), Vec3f(0, 0, 1), toLight).x, 0.f) << d;
  }
  // Away from the bound, the inverse square law is untouched.
  l.intensity = Vec3f(1.f);
  l.position = Vec3f(0.f, 0.f, 1e-3f);
  Vec3f toLight;
  EXPECT_FLOAT_EQ(unshadowedIrradiance(l, Vec3f(0.f), Vec3f(0, 0, 1), toLight).x, 1e6f);
}

TEST(NearLight, ASolutionWithALightAtAVertexIsFinite)
{
  for (const Method method : linkgi::methods())
  {
    for (const float d : { 1e-19f, 1e-21f, 1e-22f })
    {
      SCOPED_TRACE(::testing::Message() << "method " << int(method) << " distance " << d);
      SolverOptions o;
      o.method = method;
      o.raysPerVertex = 16;
      o.photonMapping.photons = 16384;
      o.photonMapping.gatherRays = 64;
      o.reference.pathsPerVertex = 16;
      o.bounces = 4;
      o.twoSided = method != Method::ImplicitVisibility; // its elements are one-sided
      Solver solver;
      const Solution& s = solver.update(squareWithLightAt(Vec3f(0.f, 0.f, d), 1e6f), o);
      for (std::size_t i = 0; i < s.elementCount(); ++i)
      {
        ASSERT_TRUE(finite(s.direct[i]) && finite(s.indirect[i]) && finite(s.radiance[i])) << i;
      }
      EXPECT_GT(s.direct[0].x, 0.f); // the light is above the front side
    }
  }
}

TEST(NearLight, ATinySceneWithALightAtAVertexIsFinite)
{
  // The SolverOptions fuzz target's edge values reach it: a square 1e-30 across (rescaled by
  // 2^100) with a light of intensity 1e-45 at 1e-45 above a corner gave an infinite direct
  // irradiance (2.3e15 / 3e-30) and radiance, which the target's finiteness check aborts on.
  Scene s = squareWithLightAt(Vec3f(0.f, 0.f, 1e-45f), 1e-45f);
  for (Vec3f& p : s.positions)
  {
    p = p * 1e-30f;
  }
  SolverOptions o;
  o.raysPerVertex = 16;
  Solver solver;
  const Solution& r = solver.update(s, o);
  for (std::size_t i = 0; i < r.elementCount(); ++i)
  {
    ASSERT_TRUE(finite(r.direct[i]) && finite(r.indirect[i]) && finite(r.radiance[i])) << i;
  }
  EXPECT_GT(r.direct[0].x, 0.f);
}
