// The reference path tracer against closed-form answers, and the error metrics.
#include "cuda/Cuda.h"
#include "linkgi/Error.h"
#include "shared/Metrics.h"
#include "methods/reference/Reference.h"
#include "shared/DirectLight.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <utility>

using namespace linkgi;

namespace
{
/// Appends a parallelogram origin + s*du + t*dv, s,t in [0,1], as an n x n grid of quads
/// (two triangles each) with one normal, albedo and emission. Returns its first vertex.
Index appendGrid(Scene& scene, Vec3f origin, Vec3f du, Vec3f dv, int n, Vec3f normal,
  Vec3f albedo, Vec3f emission = Vec3f(0.f))
{
  const auto first = static_cast<Index>(scene.positions.size());
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
    {
      scene.positions.push_back(origin + du * (float(i) / n) + dv * (float(j) / n));
      scene.normals.push_back(normal);
      scene.albedo.push_back(albedo);
      scene.emission.push_back(emission);
    }
  auto id = [&](int i, int j) { return first + static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
    {
      scene.triangles.push_back({ { id(i, j), id(i + 1, j), id(i + 1, j + 1) } });
      scene.triangles.push_back({ { id(i, j), id(i + 1, j + 1), id(i, j + 1) } });
    }
  return first;
}

/// Unit icosphere, `levels` times 1:4 subdivided, normals pointing inwards (the lit side).
Scene insideSphere(int levels, Vec3f albedo, Vec3f emission)
{
  const float t = (1.f + std::sqrt(5.f)) / 2.f;
  std::vector<Vec3f> p = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 }, { 0, -1, t },
    { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 }, { -t, 0, -1 },
    { -t, 0, 1 } };
  std::vector<Triangle> tris = { { { 0, 11, 5 } }, { { 0, 5, 1 } }, { { 0, 1, 7 } },
    { { 0, 7, 10 } }, { { 0, 10, 11 } }, { { 1, 5, 9 } }, { { 5, 11, 4 } }, { { 11, 10, 2 } },
    { { 10, 7, 6 } }, { { 7, 1, 8 } }, { { 3, 9, 4 } }, { { 3, 4, 2 } }, { { 3, 2, 6 } },
    { { 3, 6, 8 } }, { { 3, 8, 9 } }, { { 4, 9, 5 } }, { { 2, 4, 11 } }, { { 6, 2, 10 } },
    { { 8, 6, 7 } }, { { 9, 8, 1 } } };
  for (int level = 0; level < levels; ++level)
  {
    std::map<std::pair<Index, Index>, Index> midpoints;
    auto mid = [&](Index a, Index b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = midpoints.find(key);
      if (it != midpoints.end())
        return it->second;
      p.push_back((p[a] + p[b]) * 0.5f);
      return midpoints[key] = static_cast<Index>(p.size() - 1);
    };
    std::vector<Triangle> finer;
    for (const Triangle& tri : tris)
    {
      const Index a = tri.v[0], b = tri.v[1], c = tri.v[2];
      const Index ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), { { { a, ab, ca } }, { { b, bc, ab } }, { { c, ca, bc } },
                                  { { ab, bc, ca } } });
    }
    tris.swap(finer);
  }
  Scene scene;
  for (const Vec3f& q : p)
  {
    scene.positions.push_back(normalize(q));
    scene.normals.push_back(-normalize(q));
    scene.albedo.push_back(albedo);
    scene.emission.push_back(emission);
  }
  scene.triangles = tris;
  return scene;
}

/// Area-weighted mean of values[first .. first+count) (one surface of a multi-part scene).
Vec3f meanOver(const Scene& scene, const std::vector<Vec3f>& values, Index first, Index count)
{
  const std::vector<float> areas = vertexAreas(scene);
  return areaWeightedMean(std::vector<Vec3f>(values.begin() + first, values.begin() + first + count),
    std::vector<float>(areas.begin() + first, areas.begin() + first + count));
}

void expectRelNear(const Vec3f& actual, const Vec3f& expected, float rel)
{
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(actual[c], expected[c], rel * std::fabs(expected[c]) + 1e-7f) << "channel " << c;
}
}

// Closed furnace: every path stays inside and sees the same rho and Le at every hit, so the
// estimate has no variance and must equal the geometric series Le (1 + rho + ... + rho^B).
// The 1% allows for the odd ray that slips through a crack between triangles in float.
TEST(Reference, FurnaceSphereIsGeometricSeries)
{
  const float rho = 0.5f, le = 1.f;
  const Scene scene = insideSphere(2, Vec3f(rho), Vec3f(le));
  for (std::uint32_t bounces : { 1u, 3u })
  {
    ReferenceOptions options;
    options.pathsPerVertex = 64;
    options.bounces = bounces;
    const ReferenceSolution ref = solveReference(scene, options);
    const float expected = le * (1.f - std::pow(rho, float(bounces + 1))) / (1.f - rho);
    for (std::size_t v = 0; v < scene.vertexCount(); ++v)
    {
      EXPECT_EQ(ref.direct[v], Vec3f(0.f));
      const Vec3f radiance = Vec3f(le) + ref.indirect[v] * (rho / kPi);
      expectRelNear(radiance, Vec3f(expected), 0.01f);
    }
  }
}

// A point light at the centre of the closed sphere: E_d = I at every vertex, and with
// E_d = I on the whole surface B bounces add E_ind = I (rho + ... + rho^B). This checks the
// light evaluated at path vertices. 2% allows for the tessellation: hit points on the flat
// triangles lie up to ~0.3% closer to the light than the unit sphere (r^2 up to ~0.6%).
TEST(Reference, LitFurnaceSphere)
{
  const float rho = 0.5f;
  Scene scene = insideSphere(3, Vec3f(rho), Vec3f(0.f));
  Light light;
  light.intensity = { 1.f, 2.f, 4.f };
  scene.lights.push_back(light);
  ReferenceOptions options;
  options.pathsPerVertex = 64;
  options.bounces = 3;
  const ReferenceSolution ref = solveReference(scene, options);
  for (std::size_t v = 0; v < scene.vertexCount(); ++v)
  {
    expectRelNear(ref.direct[v], light.intensity, 1e-5f);
    expectRelNear(ref.indirect[v], light.intensity * (rho + rho * rho + rho * rho * rho), 0.02f);
  }
}

// Two parallel unit squares at distance 1: F = 0.19982 (Howell's catalogue, C-11). With a
// black emitter of Le = 1 the receiver's mean E_ind / pi is exactly F. 2% covers the
// trapezoid-rule quadrature of the vertex mean on a 16 x 16 grid and the Monte Carlo noise.
TEST(Reference, ParallelSquaresFormFactor)
{
  Scene scene;
  const int n = 16;
  const Index receiver = appendGrid(scene, { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, n, { 0, 0, 1 }, Vec3f(0.f));
  appendGrid(scene, { 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 }, n, { 0, 0, -1 }, Vec3f(0.f), Vec3f(1.f));
  ReferenceOptions options;
  options.pathsPerVertex = 1024;
  options.bounces = 2; // with rho = 0 everywhere, further bounces must add nothing
  const ReferenceSolution ref = solveReference(scene, options);
  const Vec3f f = meanOver(scene, ref.indirect, receiver, (n + 1) * (n + 1)) / kPi;
  expectRelNear(f, Vec3f(0.19982f), 0.02f);
}

// Perpendicular unit squares sharing an edge: F = 0.20004 (C-14). The emitter is moved back
// by a gap of 1e-3 (>> the ray offset ~2e-4): receiver vertices on the shared edge would
// otherwise start their rays inside the emitter's plane. The gap changes F by ~1e-3
// relative, well inside the same 2% as above (here a 32 x 32 grid, because the point form
// factor has a steep gradient at the shared edge).
TEST(Reference, PerpendicularSquaresFormFactor)
{
  Scene scene;
  const int n = 32;
  const float gap = 1e-3f;
  const Index receiver = appendGrid(scene, { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, n, { 0, 0, 1 }, Vec3f(0.f));
  appendGrid(scene, { -gap, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, n, { 1, 0, 0 }, Vec3f(0.f), Vec3f(1.f));
  ReferenceOptions options;
  options.pathsPerVertex = 256;
  options.bounces = 1;
  const ReferenceSolution ref = solveReference(scene, options);
  const Vec3f f = meanOver(scene, ref.indirect, receiver, (n + 1) * (n + 1)) / kPi;
  expectRelNear(f, Vec3f(0.20004f), 0.02f);
}

// Point light over a plane: direct light is evaluated in closed form, so the only error is
// float rounding (1e-5 relative). Behind an occluder the shadow ray decides, so shadowed
// vertices must be exactly 0; vertices within 0.02 of the shadow's edge are skipped, since
// the ray offset moves that edge by ~1e-4.
TEST(Reference, PointLightAndHardShadow)
{
  Scene scene;
  const int n = 20;
  const Index count = (n + 1) * (n + 1);
  appendGrid(scene, { -1, -1, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, n, { 0, 0, 1 }, Vec3f(0.5f));
  Light light;
  light.position = { 0.2f, -0.1f, 1.f };
  light.intensity = { 2.f, 1.f, 0.5f };
  scene.lights.push_back(light);
  ReferenceOptions options;
  options.pathsPerVertex = 1;
  options.bounces = 0;

  const ReferenceSolution lit = solveReference(scene, options);
  for (Index v = 0; v < count; ++v)
  {
    const Vec3f d = light.position - scene.positions[v];
    const float r2 = dot(d, d);
    expectRelNear(lit.direct[v], light.intensity * (d.z / std::sqrt(r2) / r2), 1e-5f);
    EXPECT_EQ(lit.indirect[v], Vec3f(0.f));
  }

  // A 0.5 x 0.5 occluder halfway up: the segment from q to the light crosses z = 0.5 at (q + L) / 2.
  const float half = 0.25f;
  appendGrid(scene, { -half, -half, 0.5f }, { 2 * half, 0, 0 }, { 0, 2 * half, 0 }, 2, { 0, 0, 1 }, Vec3f(0.5f));
  const ReferenceSolution shadowed = solveReference(scene, options);
  int inShadow = 0;
  for (Index v = 0; v < count; ++v)
  {
    const Vec3f crossing = (scene.positions[v] + light.position) * 0.5f;
    const float inside = half - std::max(std::fabs(crossing.x), std::fabs(crossing.y));
    if (std::fabs(inside) < 0.02f)
      continue;
    if (inside > 0.f)
    {
      EXPECT_EQ(shadowed.direct[v], Vec3f(0.f)) << "vertex " << v;
      ++inShadow;
    }
    else
      EXPECT_EQ(shadowed.direct[v], lit.direct[v]) << "vertex " << v;
  }
  EXPECT_GT(inShadow, 10); // the check above must not be vacuous
}

// Spot cone and directional light in closed form (float rounding only, 1e-5 relative).
TEST(Reference, SpotAndDirectionalLights)
{
  Scene scene;
  const int n = 20;
  appendGrid(scene, { -1, -1, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, n, { 0, 0, 1 }, Vec3f(0.5f));
  Light spot;
  spot.type = LightType::Spot;
  spot.position = { 0.f, 0.f, 1.f };
  spot.direction = { 0.f, 0.f, -1.f };
  spot.coneAngleDegrees = 30.f;
  spot.spotExponent = 2.f;
  Light sun;
  sun.type = LightType::Directional;
  sun.direction = normalize(Vec3f(0.3f, 0.f, -1.f));
  sun.intensity = { 1.f, 2.f, 3.f };
  const auto tracer = createCpuRayTracer(); // Embree, or our BVH where a build has no Embree
  tracer->build(scene.positions, scene.triangles);
  const float eps = 1e-4f;
  int inCone = 0;
  for (std::size_t v = 0; v < scene.vertexCount(); ++v)
  {
    const Vec3f p = scene.positions[v], n0 = scene.normals[v];
    const Vec3f d = spot.position - p;
    const float r = length(d), cosAxis = d.z / r; // axis is -z, so cos = dot(-z, -d / r)
    Vec3f expected(0.f);
    if (cosAxis >= std::cos(30.f * kPi / 180.f) + 1e-4f)
    {
      expected = spot.intensity * (cosAxis * cosAxis * (d.z / r) / (r * r));
      ++inCone;
    }
    else if (cosAxis > std::cos(30.f * kPi / 180.f) - 1e-4f)
      continue; // on the cone's edge: either answer is right
    expectRelNear(lightIrradiance(spot, p, n0, *tracer, eps), expected, 1e-5f);
    expectRelNear(lightIrradiance(sun, p, n0, *tracer, eps), sun.intensity * -sun.direction.z, 1e-5f);
  }
  EXPECT_GT(inCone, 10);
  EXPECT_GT(scene.vertexCount() - inCone, 10u);
}

// A plane under a constant sky sees nothing else: every ray misses and brings pi/M * Le, so
// E_ind = pi * Le up to float rounding (1e-5 relative), for any number of bounces.
TEST(Reference, ConstantEnvironmentOverPlane)
{
  Scene scene;
  appendGrid(scene, { -1, -1, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, 8, { 0, 0, 1 }, Vec3f(0.8f));
  scene.environment.color = { 0.5f, 1.f, 2.f };
  ReferenceOptions options;
  options.pathsPerVertex = 1000; // not a square: the leftover 39 paths are unstratified
  const ReferenceSolution ref = solveReference(scene, options);
  for (std::size_t v = 0; v < scene.vertexCount(); ++v)
  {
    EXPECT_EQ(ref.direct[v], Vec3f(0.f));
    expectRelNear(ref.indirect[v], scene.environment.color * kPi, 1e-5f);
  }
}

namespace
{
Scene ceilingScene(Vec3f ceilingNormal, float rho)
{
  Scene scene;
  appendGrid(scene, { -0.01f, -0.01f, 0 }, { 0.02f, 0, 0 }, { 0, 0.02f, 0 }, 2, { 0, 0, 1 }, Vec3f(0.f));
  appendGrid(scene, { -1, -1, 1 }, { 2, 0, 0 }, { 0, 2, 0 }, 4, ceilingNormal, Vec3f(rho));
  scene.environment.color = Vec3f(1.f);
  return scene;
}
}

// A tiny black receiver under a 2 x 2 ceiling at height 1 (albedo rho) in a constant sky.
// Seen from the receiver's centre the ceiling has the point form factor
// F = 4 * (1/(2 pi)) * 2 * (1/sqrt 2) * atan(1/sqrt 2) = 0.55409. The ceiling's own sky
// irradiance is pi Le (the receiver, 0.02 wide, hides < 2e-4 of it), so:
//   facing the receiver: L_ceiling = rho Le with B >= 1 (the sky counts like a light at every
//     surface, as in the link solver), E_ind = pi Le (1 - F + rho F); with B = 0 only the
//     sky seen directly counts, E_ind = pi Le (1 - F);
//   facing away (one-sided): its back blocks the sky and is black, E_ind = pi Le (1 - F).
// 1% is ten standard deviations of F estimated with 16384 stratified rays (0.1%, measured
// over 20 seeds).
TEST(Reference, CeilingReflectsSkyFrontOnly)
{
  const float rho = 0.5f;
  const Index centre = 4; // middle of the receiver's 3 x 3 vertices
  const float f = 4.f / (2.f * kPi) * 2.f / std::sqrt(2.f) * std::atan(1.f / std::sqrt(2.f));
  ReferenceOptions options;
  options.pathsPerVertex = 16384;
  for (std::uint32_t bounces : { 0u, 1u, 2u })
  {
    options.bounces = bounces;
    const ReferenceSolution facing = solveReference(ceilingScene({ 0, 0, -1 }, rho), options);
    const float seen = bounces > 0 ? rho * f : 0.f;
    expectRelNear(facing.indirect[centre], Vec3f(kPi * (1.f - f + seen)), 0.01f);
    const ReferenceSolution away = solveReference(ceilingScene({ 0, 0, 1 }, rho), options);
    expectRelNear(away.indirect[centre], Vec3f(kPi * (1.f - f)), 0.01f);
  }
}

// Two-sided: the back of a square must act exactly like the front of the same square with
// its normals flipped (same hit points, same normal -n, same random streams), so the
// receiver's front results agree to float rounding (1e-5). Back elements follow the fronts.
TEST(Reference, TwoSidedBackMatchesFlippedFront)
{
  auto build = [](Vec3f ceilingNormal) {
    Scene scene;
    appendGrid(scene, { -0.5f, -0.5f, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, 4, { 0, 0, 1 }, Vec3f(0.3f));
    appendGrid(scene, { -1, -1, 1 }, { 2, 0, 0 }, { 0, 2, 0 }, 4, ceilingNormal, Vec3f(0.6f));
    scene.environment.color = { 1.f, 0.5f, 0.25f };
    return scene;
  };
  const Scene facing = build({ 0, 0, -1 });
  const Scene away = build({ 0, 0, 1 });
  ReferenceOptions options;
  options.pathsPerVertex = 256;
  options.bounces = 3;
  const ReferenceSolution oneSided = solveReference(facing, options);
  options.twoSided = true;
  const ReferenceSolution twoSided = solveReference(away, options);
  const std::size_t n = facing.vertexCount();
  ASSERT_EQ(twoSided.indirect.size(), 2 * n);
  for (Index v = 0; v < 25; ++v) // the receiver's vertices
  {
    expectRelNear(twoSided.indirect[v], oneSided.indirect[v], 1e-5f);
    // Its back faces an empty lower half-space: pure sky, pi * Le up to rounding.
    expectRelNear(twoSided.indirect[n + v], away.environment.color * kPi, 1e-5f);
  }
}

// The link solver must converge to the reference, with every kind of source at once: sky,
// point light, emission and inter-reflection over two bounces, one- and two-sided. Direct
// light is the same closed form on both sides (float rounding, 1e-3). Indirect: measured
// 0.8% / 0.6% luminance relative RMSE at n_C = 1024 (0.3% at n_C = 4096, so it is the
// solver's sampling, not a bias); 3% flags real disagreements. The finer point of where the
// sky counts is pinned analytically by CeilingReflectsSkyFrontOnly.
TEST(Reference, AgreesWithLinkSolver)
{
  Scene scene;
  appendGrid(scene, { -1, -1, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, 12, { 0, 0, 1 }, { 0.7f, 0.5f, 0.3f });
  appendGrid(scene, { -1, -1, 1 }, { 2, 0, 0 }, { 0, 2, 0 }, 12, { 0, 0, -1 }, Vec3f(0.5f));
  appendGrid(scene, { -0.2f, 0.6f, 0.3f }, { 0.4f, 0, 0 }, { 0, 0.3f, 0 }, 2, { 0, 0, 1 }, Vec3f(0.f), Vec3f(2.f));
  Light light;
  light.position = { 0.3f, -0.2f, 0.5f };
  scene.lights.push_back(light);
  scene.environment.color = { 0.2f, 0.3f, 0.5f };
  const std::vector<float> areas = vertexAreas(scene);
  for (bool twoSided : { false, true })
  {
    SolverOptions so;
    so.raysPerVertex = 1024;
    so.bounces = 2;
    so.smoothing = false;
    so.lightOversampling = false;
    so.twoSided = twoSided;
    Solver solver;
    const Solution& sol = solver.update(scene, so);
    ReferenceOptions ro;
    ro.bounces = 2;
    ro.twoSided = twoSided;
    const ReferenceSolution ref = solveReference(scene, ro);
    std::vector<float> elementAreas = areas;
    if (twoSided)
      elementAreas.insert(elementAreas.end(), areas.begin(), areas.end());
    const ErrorMetrics direct = relativeRmse(sol.direct, ref.direct, elementAreas);
    const ErrorMetrics indirect = relativeRmse(sol.indirect, ref.indirect, elementAreas);
    std::printf("twoSided %d: direct %g indirect %g (%g %g %g)\n", twoSided, direct.relRmseLuminance,
      indirect.relRmseLuminance, indirect.relRmse.x, indirect.relRmse.y, indirect.relRmse.z);
    EXPECT_LT(direct.relRmseLuminance, 1e-3f);
    EXPECT_LT(indirect.relRmseLuminance, 0.03f);
  }
}

// Method::Reference runs the reference solver through the orchestrator: the same numbers
// as calling it directly, its tracer kept over a light move, an abort that keeps the last
// result, and no CUDA backend (said, never a failure).
TEST(Reference, AsAMethodItIsTheReferenceSolver)
{
  Scene scene;
  appendGrid(scene, { -1, -1, 0 }, { 2, 0, 0 }, { 0, 2, 0 }, 6, { 0, 0, 1 }, { 0.7f, 0.5f, 0.3f });
  appendGrid(scene, { -1, -1, 1 }, { 2, 0, 0 }, { 0, 2, 0 }, 6, { 0, 0, -1 }, Vec3f(0.5f));
  Light light;
  light.position = { 0.3f, -0.2f, 0.5f };
  scene.lights.push_back(light);
  scene.environment.color = { 0.2f, 0.3f, 0.5f };
  SolverOptions so;
  so.method = Method::Reference;
  so.reference.pathsPerVertex = 64;
  so.bounces = 2;
  so.seed = 3;
  ReferenceOptions ro;
  ro.pathsPerVertex = 64;
  ro.bounces = 2;
  ro.seed = 3;
  for (bool twoSided : { false, true })
  {
    so.twoSided = ro.twoSided = twoSided;
    Solver solver;
    const Solution first = solver.update(scene, so);
    const ReferenceSolution ref = solveReference(scene, ro);
    EXPECT_EQ(first.direct, ref.direct) << "two-sided " << twoSided;
    EXPECT_EQ(first.indirect, ref.indirect) << "two-sided " << twoSided << ": no smoothing";
    ASSERT_EQ(first.radiance.size(), ref.direct.size());
    const Vec3f expected = scene.albedo[5] * (ref.direct[5] + ref.indirect[5]) * (1.f / kPi);
    EXPECT_FLOAT_EQ(first.radiance[5].x, expected.x);
    const SolverStats& st = solver.stats();
    EXPECT_EQ(st.method, "reference");
    EXPECT_EQ(st.counter("Paths"), ref.direct.size() * 64u);
    EXPECT_TRUE(st.ran("Geometry") && st.ran("Paths"));
    EXPECT_TRUE(st.warnings.empty()) << st.warnings.front();
    EXPECT_NE(st.backendNote.find("no CUDA backend"), std::string::npos) << st.backendNote;

    Scene moved = scene;
    moved.lights[0].position.x += 0.2f;
    solver.update(moved, so);
    EXPECT_FALSE(solver.stats().ran("Geometry")) << "a light move keeps the tracer";
    EXPECT_EQ(solver.solution().indirect, solveReference(moved, ro).indirect);

    Scene again = scene;
    again.lights[0].position.y += 0.2f;
    EXPECT_THROW(solver.update(again, so, [](const char*, double) { return false; }), Aborted);
    EXPECT_EQ(solver.solution().indirect, solveReference(moved, ro).indirect) << "the last result stays";
  }
  so.twoSided = false;
  so.backend = Backend::Cuda;
  Solver solver;
  solver.update(scene, so);
  EXPECT_EQ(solver.stats().backend, "cpu");
  ASSERT_EQ(solver.stats().warnings.size(), 1u);
  // A build with CUDA says the method has none; one without says the build has none.
  const char* expected = cuda::compiled() ? "'reference' has no CUDA backend" : "CUDA backend not available";
  EXPECT_NE(solver.stats().warnings[0].find(expected), std::string::npos) << solver.stats().warnings[0];
  so.reference.pathsPerVertex = 0;
  EXPECT_THROW(solver.update(scene, so), Error) << "its option is checked";
}

// Same seed, same answer (per-path random streams do not depend on scheduling); another
// seed gives another estimate of a noisy quantity.
TEST(Reference, DeterministicForSeed)
{
  Scene scene;
  appendGrid(scene, { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, 4, { 0, 0, 1 }, Vec3f(0.5f));
  appendGrid(scene, { 0, 0, 1 }, { 1, 0, 0 }, { 0, 1, 0 }, 4, { 0, 0, -1 }, Vec3f(0.5f), Vec3f(1.f));
  ReferenceOptions options;
  options.pathsPerVertex = 37;
  const ReferenceSolution a = solveReference(scene, options);
  const ReferenceSolution b = solveReference(scene, options);
  options.seed = 2;
  const ReferenceSolution c = solveReference(scene, options);
  EXPECT_EQ(a.indirect, b.indirect);
  EXPECT_NE(a.indirect, c.indirect);
}

TEST(Reference, RejectsBadInputAndHonoursAbort)
{
  Scene scene;
  appendGrid(scene, { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, 2, { 0, 0, 1 }, Vec3f(0.5f));
  Scene noNormals = scene;
  noNormals.normals.pop_back();
  EXPECT_THROW(solveReference(noNormals), Error);
  Scene badIndex = scene;
  badIndex.triangles[0].v[2] = 1000;
  EXPECT_THROW(solveReference(badIndex), Error);
  ReferenceOptions options;
  options.pathsPerVertex = 4;
  EXPECT_THROW(solveReference(scene, options, [](const char*, double) { return false; }), Aborted);
}

// Metrics are exact arithmetic on small inputs: tolerances are float rounding only.
TEST(Metrics, RelativeRmse)
{
  const std::vector<Vec3f> ref = { { 1, 2, 3 }, { 0.5f, 0.1f, 4 }, { 2, 2, 0.2f } };
  const std::vector<float> areas = { 1.f, 0.5f, 2.f };
  const ErrorMetrics same = relativeRmse(ref, ref, areas);
  EXPECT_EQ(same.relRmse, Vec3f(0.f));
  EXPECT_EQ(same.relRmseLuminance, 0.f);

  const float e = 0.05f;
  std::vector<Vec3f> scaled;
  for (const Vec3f& r : ref)
    scaled.push_back(r * (1.f + e));
  const ErrorMetrics m = relativeRmse(scaled, ref, areas);
  expectRelNear(m.relRmse, Vec3f(e), 1e-4f);
  EXPECT_NEAR(m.relRmseLuminance, e, 1e-4f * e);

  EXPECT_THROW(relativeRmse(ref, scaled, { 1.f, 2.f }), Error);
  EXPECT_THROW(relativeRmse(ref, { { 1, 1, 1 } }, areas), Error);
}

TEST(Metrics, VertexAreasAndMean)
{
  Scene scene;
  appendGrid(scene, { 0, 0, 0 }, { 2, 0, 0 }, { 0, 3, 0 }, 3, { 0, 0, 1 }, Vec3f(0.5f));
  const std::vector<float> areas = vertexAreas(scene);
  double total = 0;
  for (float a : areas)
    total += a;
  EXPECT_NEAR(total, 6.0, 1e-5); // the areas partition the surface
  // Corner vertex 0 belongs to the two triangles of one 2/3 x 1 cell: (2/3) / 3.
  EXPECT_NEAR(areas[0], 2.f / 9.f, 1e-6f);

  std::vector<Vec3f> values(areas.size(), Vec3f(1.f, 2.f, 3.f));
  expectRelNear(areaWeightedMean(values, areas), Vec3f(1.f, 2.f, 3.f), 1e-6f);
  values[0] = Vec3f(0.f); // only vertex 0 changes: the mean drops by its share of the area
  expectRelNear(areaWeightedMean(values, areas), Vec3f(1.f, 2.f, 3.f) * (1.f - (2.f / 9.f) / 6.f), 1e-5f);
  EXPECT_THROW(areaWeightedMean(values, { 1.f }), Error);
}
