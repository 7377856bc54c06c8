// Photon mapping (Method::PhotonMapping): the photons carry the lights' power, the
// clustering's metric and coverage, agreement with the reference and the furnace, and what
// each change re-runs.
#include "CudaFixtures.h"
#include "SceneFixtures.h"

#include "methods/pm/PhotonMapping.h"
#include "methods/pm/PmBackends.h"
#include "methods/pm/PmTypes.h"

#include "methods/links/Links.h"
#include "shared/Metrics.h"
#include "shared/RayTracer.h"
#include "methods/reference/Reference.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace linkgi;

namespace
{
SolverOptions photonMapping()
{
  SolverOptions o;
  o.method = Method::PhotonMapping;
  o.backend = Backend::Cpu;
  return o;
}

/// The reference solution of s with 256 paths per vertex and the bounces of o.
ReferenceSolution referenceOf(const Scene& s, const SolverOptions& o)
{
  ReferenceOptions ro;
  ro.pathsPerVertex = 256;
  ro.bounces = o.bounces;
  return solveReference(s, ro);
}

/// A closed cube of side 2 about the origin, faces inward, albedo rho, a point light inside.
Scene closedBox(float rho, int n = 8)
{
  Scene s;
  for (int axis = 0; axis < 3; ++axis)
  {
    for (float side : { -1.f, 1.f })
    {
      const Index base = Index(s.positions.size());
      for (int i = 0; i <= n; ++i)
      {
        for (int j = 0; j <= n; ++j)
        {
          Vec3f p(0.f);
          p[axis] = side;
          p[(axis + 1) % 3] = -1.f + 2.f * float(i) / float(n);
          p[(axis + 2) % 3] = -1.f + 2.f * float(j) / float(n);
          Vec3f normal(0.f);
          normal[axis] = -side;
          s.positions.push_back(p);
          s.normals.push_back(normal);
          s.albedo.push_back(Vec3f(rho));
        }
      }
      for (int i = 0; i < n; ++i)
      {
        for (int j = 0; j < n; ++j)
        {
          const Index a = base + Index(i * (n + 1) + j), b = a + Index(n + 1);
          s.triangles.push_back({ { a, b, Index(b + 1) } });
          s.triangles.push_back({ { a, Index(b + 1), Index(a + 1) } });
        }
      }
    }
  }
  Light l;
  l.position = Vec3f(0.2f, -0.1f, 0.3f);
  l.intensity = Vec3f(2.f, 1.f, 0.5f);
  s.lights.push_back(l);
  return s;
}

std::vector<Vec3f> total(const Solution& s)
{
  std::vector<Vec3f> t(s.direct.size());
  for (std::size_t i = 0; i < t.size(); ++i)
  {
    t[i] = s.direct[i] + s.indirect[i];
  }
  return t;
}
}

TEST(TestPhotonMapping, PhotonsInAClosedBoxCarryTheLightsPower)
{
  // One bounce: every photon is a first hit, and reflects rho times what the light sent its
  // way; the light's 4 pi I all lands on the box.
  Scene s = closedBox(0.6f);
  validateScene(s);
  const std::unique_ptr<RayTracer> tracer = createCpuRayTracer();
  tracer->build(s.positions, s.triangles);
  SolverOptions o = photonMapping();
  o.bounces = 1;
  o.photonMapping.photons = 20000;
  pm::PhotonMap map;
  pm::tracePhotons(s, frontFaceNormals(s), rayOrigins(s, Topology::build(s.vertexCount(), s.triangles)), *tracer, o, map);
  ASSERT_GT(map.count(), 19000u);
  const Vec3f sum = map.totalFlux(), expected = s.lights[0].intensity * (4.f * kPi * 0.6f);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(sum[c] / expected[c], 1.0, 1e-4) << "channel " << c;
  }
  // Three bounces with Russian roulette: rho + rho^2 + rho^3 of it, within the sampling noise.
  o.bounces = 3;
  pm::tracePhotons(s, frontFaceNormals(s), rayOrigins(s, Topology::build(s.vertexCount(), s.triangles)), *tracer, o, map);
  const double series = 0.6 + 0.36 + 0.216;
  EXPECT_NEAR(map.totalFlux().x / (expected.x / 0.6 * series), 1.0, 0.03);
}

TEST(TestPhotonMapping, ClusterMetricIsThePapers)
{
  const Vec3f up(0, 0, 1), down(0, 0, -1), side(1, 0, 0);
  EXPECT_FLOAT_EQ(pm::clusterMetric(Vec3f(1, 2, 3), up, Vec3f(1, 2, 3), up, 0.3f), 0.f);
  EXPECT_NEAR(pm::clusterMetric(Vec3f(0.f), up, Vec3f(0.f), down, 0.3f), 2.f, 1e-6);
  EXPECT_NEAR(pm::clusterMetric(Vec3f(0.f), up, Vec3f(0.f), side, 0.3f), std::sqrt(2.f), 1e-6);
  // alpha |x - c|: alpha is per unit of distance here (the caller divides by the diagonal).
  EXPECT_NEAR(pm::clusterMetric(Vec3f(0.f), up, Vec3f(2, 0, 0), up, 0.25f), 0.5f, 1e-6);
}

TEST(TestPhotonMapping, ClustersCoverEveryVertexOnce)
{
  const Scene s = makeStandardScene("cornell");
  for (std::uint32_t k : { 1u, 37u, 1024u, 1u << 20 })
  {
    const pm::Clusters c = pm::clusterVertices(s, k, 0.3f, 4);
    ASSERT_GE(c.count(), 1u);
    // Beyond k, the vertices that no sample near them serves are samples of their own.
    EXPECT_LE(c.count(), s.vertexCount());
    ASSERT_EQ(c.assignment.size(), s.vertexCount());
    std::vector<int> members(c.count(), 0);
    for (std::size_t v = 0; v < s.vertexCount(); ++v)
    {
      ASSERT_LT(c.assignment[v], c.count());
      ++members[c.assignment[v]];
      EXPECT_EQ(c.neighbours[v * pm::Clusters::kInterpolants], c.assignment[v]) << "own cluster first";
    }
    for (std::size_t j = 0; j < c.count(); ++j)
    {
      EXPECT_GT(members[j], 0) << "cluster " << j << " of " << k;
      EXPECT_EQ(c.assignment[c.sample[j]], Index(j)) << "a sample belongs to its cluster";
    }
    if (k == 1024u)
    {
      // The box's walls meet at right angles: no cluster spans two of them.
      for (std::size_t v = 0; v < s.vertexCount(); ++v)
      {
        EXPECT_GT(dot(s.normals[v], s.normals[c.sample[c.assignment[v]]]), 0.5f);
      }
    }
  }
}

TEST(TestPhotonMapping, FurnaceConvergesToLeOverOneMinusRho)
{
  // Closed sphere, rho = 0.5, Le = 1: L = 2 (12 bounces leave 1.2e-4 of it out).
  const Scene s = makeStandardScene("furnace");
  SolverOptions o = photonMapping();
  o.bounces = 12;
  Solver solver;
  const Solution& sol = solver.update(s, o);
  double worst = 0;
  for (std::size_t v = 0; v < s.vertexCount(); ++v)
  {
    worst = std::max(worst, std::abs(sol.radiance[v].x * (1.0 - s.albedo[v].x) / s.emission[v].x - 1.0));
  }
  EXPECT_LT(worst, 0.03);
}

TEST(TestPhotonMapping, AgreesWithReference)
{
  // The room with a block: total irradiance against per-vertex path tracing (2048 paths, the
  // same 3 bounces); the bound is 8%.
  const Scene s = test::roomWithBlock(0.25f);
  const std::vector<Vec3f> reference = test::referenceTotal(s, 2048, 3);
  Solver solver;
  const ErrorMetrics err = relativeRmse(total(solver.update(s, photonMapping())), reference, vertexAreas(s));
  std::printf("room: relative RMSE luminance %.4f (worst channel %.4f)\n", err.relRmseLuminance, maxComponent(err.relRmse));
  EXPECT_LE(err.relRmseLuminance, 0.08f);
}

TEST(TestPhotonMapping, StagesRerunOnlyWhatChanged)
{
  const Scene s = test::roomWithBlock(0.5f);
  SolverOptions o = photonMapping();
  o.photonMapping.photons = 20000;
  Solver solver;
  solver.update(s, o);
  const SolverStats& st = solver.stats();
  EXPECT_EQ(st.method, "photon-mapping");
  EXPECT_GT(st.counter("Photons"), 0u);
  EXPECT_GT(st.counter("Clusters"), 0u);
  for (const char* stage : { "Geometry", "Photons", "Clusters", "LightLinks", "Gather", "Finish" })
  {
    EXPECT_TRUE(st.ran(stage)) << stage;
  }

  Scene lit = s; // a light move: photons, direct light, gather; not the clusters
  lit.lights[0].position.x += 0.2f;
  solver.update(lit, o);
  EXPECT_FALSE(st.ran("Geometry") || st.ran("Clusters"));
  EXPECT_TRUE(st.ran("Photons") && st.ran("LightLinks") && st.ran("Gather"));
  EXPECT_EQ(st.runs("ClusterBuilds"), 1u);
  EXPECT_EQ(st.runs("PhotonTraces"), 2u);

  Scene moved = lit; // a deformation: everything
  for (Vec3f& p : moved.positions)
  {
    p.y *= 1.02f;
  }
  solver.update(moved, o);
  EXPECT_TRUE(st.ran("Geometry") && st.ran("Clusters") && st.ran("Photons") && st.ran("Gather"));

  o.smoothing = true; // only the finish
  solver.update(moved, o);
  EXPECT_FALSE(st.ran("Photons") || st.ran("Gather") || st.ran("Clusters"));
  EXPECT_TRUE(st.ran("Finish"));
}

TEST(TestPhotonMapping, DeterministicForASeedOnAnyThreadCount)
{
  const Scene s = test::roomWithBlock(0.5f);
  SolverOptions o = photonMapping();
  o.photonMapping.photons = 20000;
  Solver a, b;
  const Solution first = a.update(s, o);
  Solution single;
  runWithConcurrency(1, [&] { single = b.update(s, o); });
  EXPECT_TRUE(sameBits(first.indirect, single.indirect));
}

TEST(TestPhotonMapping, BadOptionsAreNamed)
{
  SolverOptions o = photonMapping();
  o.photonMapping.gatherRays = 200;
  EXPECT_NE(test::errorOf([&] { validateOptions(o); }).find("final-gather rays"), std::string::npos);
  o = photonMapping();
  o.photonMapping.photons = 0;
  EXPECT_NE(test::errorOf([&] { validateOptions(o); }).find("photons"), std::string::npos);
  o = photonMapping();
  o.photonMapping.estimatePhotons = 1;
  EXPECT_NE(test::errorOf([&] { validateOptions(o); }).find("radiance estimate"), std::string::npos);
  o = photonMapping();
  o.photonMapping.alpha = std::nanf("");
  EXPECT_NE(test::errorOf([&] { validateOptions(o); }).find("alpha"), std::string::npos);
}

TEST(TestPhotonMapping, MaterialsAreValidated)
{
  Scene s = test::twoSquares(false, 2);
  s.triangleMaterials.assign(s.triangleCount(), MaterialType::Diffuse);
  s.triangleMaterials[1] = MaterialType(7);
  EXPECT_NE(test::errorOf([&] { validateScene(s); }).find("material 7"), std::string::npos);
  s.triangleMaterials.pop_back();
  s.triangleMaterials[1] = MaterialType::Glass;
  EXPECT_NE(test::errorOf([&] { validateScene(s); }).find("one per triangle"), std::string::npos);
  s.triangleMaterials.assign(s.triangleCount(), MaterialType::Glass);
  for (const float bad : { 0.f, -1.5f, std::nanf(""), INFINITY })
  {
    s.triangleIor.assign(s.triangleCount(), 1.5f);
    s.triangleIor[0] = bad;
    EXPECT_NE(test::errorOf([&] { validateScene(s); }).find("index of refraction"), std::string::npos) << bad;
  }
  // A degenerate triangle goes, and its material and index with it.
  Scene d = test::twoSquares(false, 2);
  d.triangles.push_back({ { 0, 0, 1 } });
  d.triangleMaterials.assign(d.triangleCount(), MaterialType::Diffuse);
  d.triangleMaterials.back() = MaterialType::Mirror;
  d.triangleIor.assign(d.triangleCount(), 1.5f);
  validateScene(d);
  EXPECT_EQ(d.triangleMaterials.size(), d.triangleCount());
  EXPECT_EQ(d.triangleIor.size(), d.triangleCount());
  EXPECT_FALSE(d.hasSpecular());
}

TEST(TestPhotonMapping, OtherMethodsSayTheyLightGlassAsDiffuse)
{
  const Scene s = makeStandardScene("cornell-glass");
  Solver solver;
  SolverOptions o = test::quickOptions();
  solver.update(s, o);
  const auto& w = solver.stats().warnings;
  EXPECT_TRUE(std::any_of(w.begin(), w.end(), [](const std::string& m) { return m.find("as diffuse") != std::string::npos; }));
  EXPECT_TRUE(solver.solution().caustics.empty());
}

TEST(TestPhotonMapping, CausticsAgreeWithLightTracing)
{
  // The glass ball and the mirror band: the brightest caustic vertex is the reference's or a
  // neighbour, and the caustic power is within 10%.
  const Scene s = makeStandardScene("caustics");
  const std::vector<Vec3f> ref = solveCausticReference(s, 1u << 22, 1);
  Solver solver;
  SolverOptions o = photonMapping();
  o.smoothing = false; // smoothing blurs E_ind, caustics included, not the caustics array
  const Solution& sol = solver.update(s, o);
  ASSERT_EQ(sol.caustics.size(), sol.indirect.size());
  Scene checked = s;
  validateScene(checked);
  const std::vector<float> area = vertexAreas(checked);
  double power = 0, refPower = 0;
  std::size_t peak = 0, refPeak = 0;
  for (std::size_t v = 0; v < checked.vertexCount(); ++v)
  {
    power += sol.caustics[v].y * area[v];
    refPower += ref[v].y * area[v];
    peak = sol.caustics[v].y > sol.caustics[peak].y ? v : peak;
    refPeak = ref[v].y > ref[refPeak].y ? v : refPeak;
    EXPECT_LE(sol.caustics[v].y, sol.indirect[v].y * 1.0001f + 1e-6f) << "caustics are part of E_ind";
  }
  std::printf("caustic power %.4f, reference %.4f; peaks %.4f apart\n", power, refPower,
    length(checked.positions[peak] - checked.positions[refPeak]));
  EXPECT_GT(refPower, 0.3);
  EXPECT_NEAR(power / refPower, 1.0, 0.10);
  EXPECT_LE(length(checked.positions[peak] - checked.positions[refPeak]), 0.0201f * 1.42f); // a diagonal cell
}

TEST(TestPhotonMapping, NothingLightsAPlateUnderATableTop)
{
  // A plate facing up 1 mm under the whole of a table top sees only the top's underside,
  // which no light reaches but through the gap: it is dark, as the reference finds. The top's
  // upper face is brightly lit and faces the same way 6 cm above, and the floor lit below, so
  // with clusters that span them the plate's vertices must interpolate neither the upper
  // face's samples nor the floor's, nor the upper face the plate's. (With far fewer clusters
  // than here, a face without samples near it still reads those of a parallel face more than
  // 10 times its gap away, which the tangent-plane test lets through.)
  MeshBuilder b;
  b.addBox({ -2, 0, -2 }, { 2, 3, 2 }, 0.25f, Vec3f(0.5f), true);
  const Index top = b.vertexCount();
  b.addBox({ -1, 0.75f, -0.6f }, { 1, 0.8f, 0.6f }, 0.25f, Vec3f(0.5f));
  const Index plate = b.vertexCount();
  b.addQuadGrid({ -1, 0.749f, 0.6f }, { 2, 0, 0 }, { 0, 0, -1.2f }, 16, 10, Vec3f(0.5f));
  const Index end = b.vertexCount();
  Scene s = b.take();
  Light l;
  l.position = { 0.3f, 2.5f, 0.4f };
  l.intensity = Vec3f(10.f);
  s.lights.push_back(l);
  SolverOptions o = photonMapping();
  o.photonMapping.clusters = 1024; // about two vertices each: every surface has samples of its own
  Solver solver;
  const Solution& sol = solver.update(s, o);
  const ReferenceSolution reference = referenceOf(s, o);
  const double upper = test::meanLuminance(s, sol.indirect, top, plate, 1),
               truth = test::meanLuminance(s, reference.indirect, top, plate, 1),
               lit = test::meanLuminance(s, sol.indirect, plate, end, 0),
               dark = test::meanLuminance(s, reference.indirect, plate, end, 0);
  std::printf("table top's upper face %.4g W/m^2 indirect (the reference's %.4g); the plate %.4g (%.4g)\n",
    upper, truth, lit, dark);
  EXPECT_LT(dark, 0.1 * truth);
  EXPECT_LT(lit, 0.1 * truth) << "the plate reads the top's light";
  EXPECT_NEAR(upper, truth, 0.2 * truth) << "the top reads the plate's darkness";
}

// Both backends trace the same Halton light paths (a hit may differ where a path grazes an
// edge), so the photon maps, the estimates and the gathers agree: on the Cornell box, after a
// light move, and on the caustic scene with its caustics.
TEST(TestPhotonMapping, CpuAndCudaBackendsAgree)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  for (const char* name : { "cornell", "caustics" })
  {
    const Scene s = makeStandardScene(name);
    SolverOptions o = photonMapping();
    Solver cpu, gpu;
    for (int step = 0; step < 2; ++step)
    {
      Scene now = s;
      if (step == 1)
      {
        now.lights[0].position.x += 0.05f * boundingDiagonal(s.positions);
      }
      const Solution& a = cpu.update(now, test::onBackend(Backend::Cpu, o));
      const Solution& b = gpu.update(now, test::onBackend(Backend::Cuda, o));
      ASSERT_EQ(gpu.stats().backend, "cuda") << (gpu.stats().warnings.empty() ? "" : gpu.stats().warnings[0]);
      const double photons = double(cpu.stats().counter("Photons"));
      EXPECT_NEAR(double(gpu.stats().counter("Photons")) / photons, 1.0, 1e-3) << name << ", step " << step;
      EXPECT_EQ(gpu.stats().counter("Clusters"), cpu.stats().counter("Clusters")) << name;
      const float direct = test::relativeError(b.direct, a.direct);
      const float indirect = test::relativeError(b.indirect, a.indirect);
      std::printf("%s step %d: photons %zu / %zu, relative RMSE direct %.5f, indirect %.5f\n", name, step,
        std::size_t(gpu.stats().counter("Photons")), std::size_t(cpu.stats().counter("Photons")), direct, indirect);
      EXPECT_LT(direct, 0.01f) << name << ", step " << step;
      EXPECT_LT(indirect, 0.03f) << name << ", step " << step;
      ASSERT_EQ(b.caustics.size(), a.caustics.size()) << name;
      if (!a.caustics.empty())
      {
        const float caustics = test::relativeError(b.caustics, a.caustics);
        std::printf("%s step %d: caustics relative RMSE %.5f\n", name, step, caustics);
        EXPECT_LT(caustics, 0.05f) << name << ", step " << step;
      }
    }
  }
}
