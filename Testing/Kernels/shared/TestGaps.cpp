// Gaps (shared/Gaps.h): a hit under a surface nearly parallel to it reads nothing from the
// corners or samples out in the open, and the methods that test for gaps do not light the
// floor under a resting object from the lit floor beside it.
#include "SceneFixtures.h"

#include "linkgi/Solver.h"
#include "shared/Gaps.h"
#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"
#include "shared/Surface.h"

#include <gtest/gtest.h>

#include <memory>

using namespace linkgi;

namespace
{
/// A floor of 2 x 2 m at y = 0, four triangles fanned about vertex 0 at `fan`, and a plate
/// of 1 x 1 m, 2 mm over the floor's middle. A ray from the plate's underside to the floor's
/// point `at` makes the hit.
struct FloorUnderAPlate
{
  Scene scene;
  std::vector<Vec3f> faceNormals;
  std::vector<RayOrigin> origins;
  std::unique_ptr<RayTracer> tracer;

  explicit FloorUnderAPlate(const Vec3f& fan)
  {
    const Vec3f up(0, 1, 0);
    const auto vertex = [this](Vec3f p, Vec3f n) {
      scene.positions.push_back(p);
      scene.normals.push_back(n);
      scene.albedo.push_back(Vec3f(0.5f));
      return Index(scene.positions.size() - 1);
    };
    vertex(fan, up);
    const Index c[4] = { vertex({ 1, 0, 1 }, up), vertex({ 1, 0, -1 }, up), vertex({ -1, 0, -1 }, up),
      vertex({ -1, 0, 1 }, up) };
    for (int k = 0; k < 4; ++k)
    {
      scene.triangles.push_back({ { 0, c[k], c[(k + 1) % 4] } });
    }
    const Index p[4] = { vertex({ 0.5f, 0.002f, 0.5f }, -up), vertex({ -0.5f, 0.002f, 0.5f }, -up),
      vertex({ -0.5f, 0.002f, -0.5f }, -up), vertex({ 0.5f, 0.002f, -0.5f }, -up) };
    scene.triangles.push_back({ { p[0], p[1], p[2] } });
    scene.triangles.push_back({ { p[0], p[2], p[3] } });
    faceNormals = frontFaceNormals(scene);
    origins = rayOrigins(scene, Topology::build(scene.vertexCount(), scene.triangles));
    tracer = createCpuRayTracer();
    tracer->build(scene.positions, scene.triangles);
  }

  /// The hit of a ray from `from` to the floor's point `at`, its corners in a gap left out.
  Hit hitAt(const Vec3f& from, const Vec3f& at) const
  {
    Ray ray;
    ray.origin = from;
    ray.direction = at - from;
    ray.tfar = 2.f;
    Hit h;
    tracer->trace(&ray, &h, 1);
    EXPECT_NE(h.triangle, kInvalidIndex);
    EXPECT_NEAR(h.t, 1.f, 1e-4f);
    excludeGapCorners(h, ray, scene.triangles.data(), scene.positions.data(), faceNormals.data(), origins.data(),
      false, ClosestHit{ *tracer });
    return h;
  }
};

float weightOf(const FloorUnderAPlate& f, const Hit& h, Index vertex)
{
  const Triangle& t = f.scene.triangles[h.triangle];
  const float bary[3] = { 1.f - h.u - h.v, h.u, h.v };
  float w = 0.f;
  for (int k = 0; k < 3; ++k)
  {
    w += t.v[k] == vertex ? bary[k] : 0.f;
  }
  return w;
}
}

TEST(TestGaps, AHitUnderACoverReadsOnlyTheCornersUnderItToo)
{
  const FloorUnderAPlate f({ 0, 0, 0 });
  // Under the plate, 0.3 m from the centre: the centre is under the plate too, the two outer
  // corners are out in the open, 1.2 m away. The hit reads the centre alone.
  const Hit under = f.hitAt({ 0.29f, 0.0019f, 0.02f }, { 0.3f, 0, 0.05f });
  EXPECT_FALSE(isGapHit(under));
  EXPECT_FLOAT_EQ(weightOf(f, under, 0), 1.f);

  // Out in the open, beside the plate: nothing covers the hit, which keeps its barycentrics.
  const Vec3f outside(0.8f, 0, 0.1f);
  Ray ray{ { 0.8f, 0.5f, 0.1f }, 0.f, outside - Vec3f(0.8f, 0.5f, 0.1f), 2.f };
  Hit open;
  f.tracer->trace(&ray, &open, 1);
  const Hit kept = f.hitAt({ 0.8f, 0.5f, 0.1f }, outside);
  EXPECT_FALSE(isGapHit(kept));
  EXPECT_EQ(kept.triangle, open.triangle);
  EXPECT_FLOAT_EQ(kept.u, open.u);
  EXPECT_FLOAT_EQ(kept.v, open.v);
}

TEST(TestGaps, AHitWhoseCornersAreAllOutsideItsGapReadsNothing)
{
  // The floor fanned about the middle of its edge: the triangle under the plate's middle has
  // every corner out in the open, and the hit there reads nothing (as a back).
  const FloorUnderAPlate f({ 0, 0, 1 });
  const Hit h = f.hitAt({ -0.2f, 0.0019f, 0.f }, { -0.2f, 0, 0.02f });
  EXPECT_TRUE(isGapHit(h));

  // The same point from a receiver farther than its corners, whose ray slides under the
  // plate: no gap is assumed (a receiver that far cannot be what covers the hit).
  EXPECT_FALSE(isGapHit(f.hitAt({ -0.2f, 0.0019f, 2.f }, { -0.2f, 0, 0.02f })));
}

TEST(TestGaps, GatherHitsDoNotLightTheUndersideOfASlabOnTheFloor)
{
  // The slab's underside sees only the floor under it, which the light reaches only through
  // the 2 mm gap: nearly dark, as the reference finds. The floor's triangles under the slab
  // have their corners out in the lit floor, and no method that tests its gather hits for a
  // gap may read them there: instant radiosity's compensation interpolates those corners
  // (excludeGapCorners), photon mapping reads estimates made out there, implicit visibility
  // leaves drawn there. (The link method's rows have no such test, for its cost in link
  // generation: 0.185 here; Methods.md, "Link structure".)
  Index slab = 0;
  const Scene s = test::slabOnTheFloor(slab);
  const Index end = Index(s.vertexCount());
  ReferenceOptions ro;
  ro.pathsPerVertex = 256;
  const ReferenceSolution reference = solveReference(s, ro);
  const double dark = test::meanLuminance(s, reference.indirect, slab, end, -1),
               top = test::meanLuminance(s, reference.indirect, slab, end, 1);
  std::printf("the slab's underside: reference %.4g W/m^2 indirect (its top's %.4g)\n", dark, top);
  EXPECT_LT(dark, 0.1 * top);
  for (Method method : { Method::InstantRadiosity, Method::ImplicitVisibility, Method::PhotonMapping })
  {
    SolverOptions o;
    o.method = method;
    o.backend = Backend::Cpu;
    Solver solver;
    const double lit = test::meanLuminance(s, solver.update(s, o).indirect, slab, end, -1);
    std::printf("  %s: %.4g\n", methodName(method), lit);
    // Instant radiosity 0.041, implicit visibility 0.109 and photon mapping 0.046 against
    // the reference's 0.061 and the top's 2.36. Reading the lit floor's corners and
    // estimates, instant radiosity was 0.179 and photon mapping 0.22.
    EXPECT_LT(lit, dark + 0.03 * top) << methodName(method) << ": the lit floor lights the floor under the slab";
    EXPECT_GT(lit, 0.25 * dark) << methodName(method) << ": the light through the gap is lost";
  }
}
