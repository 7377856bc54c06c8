// findInwardSurfaces, hasLightInside, litOnlyFromBehind and litShareOfFronts on shapes whose
// inside and outside are known: closed surfaces wound either way, surfaces with small holes,
// open surfaces (a bowl, a tube) that have no inside, and a room with its lamp inside.
#include "CudaFixtures.h"

#include "linkgi/Orientation.h"
#include "scene/BackLit.h"
#include "linkgi/Solver.h"
#include "scene/MeshBuilder.h"
#include "shared/RayTracer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

using namespace linkgi;

namespace
{
/// A latitude-longitude sphere of radius r around c, normals outward (or inward), from
/// polar angle 0 down to `endTheta` (pi: closed; pi/2: a bowl); the poles are single points.
Scene Sphere(const Vec3f& c, float r, float endTheta, bool inward, int rings = 24, int segments = 32)
{
  Scene s;
  const bool closed = endTheta >= kPi;
  const int lastRing = closed ? rings - 1 : rings;
  s.positions.push_back(c + Vec3f(0.f, 0.f, r));
  for (int i = 1; i <= lastRing; ++i)
  {
    const float t = endTheta * float(i) / float(rings);
    for (int j = 0; j < segments; ++j)
    {
      const float p = 2.f * kPi * float(j) / float(segments);
      s.positions.push_back(c + Vec3f(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)) * r);
    }
  }
  if (closed)
  {
    s.positions.push_back(c + Vec3f(0.f, 0.f, -r));
  }
  const auto ring = [&](int i, int j) { return Index(1 + (i - 1) * segments + (j % segments)); };
  const auto add = [&](Index a, Index b, Index d) {
    s.triangles.push_back(inward ? Triangle{ { a, d, b } } : Triangle{ { a, b, d } });
  };
  for (int j = 0; j < segments; ++j)
  {
    add(0, ring(1, j), ring(1, j + 1));
    for (int i = 1; i < lastRing; ++i)
    {
      add(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
      add(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
    }
    if (closed)
    {
      add(ring(lastRing, j), Index(s.positions.size() - 1), ring(lastRing, j + 1));
    }
  }
  for (const Vec3f& p : s.positions)
  {
    s.normals.push_back(normalize(p - c) * (inward ? -1.f : 1.f));
  }
  return s;
}

/// A tube of radius 1 along z from 0 to 2, open at both ends, normals outward or inward.
Scene Tube(bool inward)
{
  Scene s;
  const int segments = 32;
  for (int k = 0; k < 2; ++k)
  {
    for (int j = 0; j < segments; ++j)
    {
      const float p = 2.f * kPi * float(j) / float(segments);
      s.positions.push_back({ std::cos(p), std::sin(p), 2.f * float(k) });
      s.normals.push_back(Vec3f(std::cos(p), std::sin(p), 0.f) * (inward ? -1.f : 1.f));
    }
  }
  for (int j = 0; j < segments; ++j)
  {
    const Index a = Index(j), b = Index((j + 1) % segments), d = a + segments, e = b + segments;
    s.triangles.push_back(inward ? Triangle{ { a, d, b } } : Triangle{ { a, b, d } });
    s.triangles.push_back(inward ? Triangle{ { b, d, e } } : Triangle{ { b, e, d } });
  }
  return s;
}

bool NormalsEqual(const Scene& a, const Scene& b, float sign)
{
  for (std::size_t v = 0; v < a.vertexCount(); ++v)
  {
    if (!(a.normals[v] == b.normals[v] * sign))
    {
      return false;
    }
  }
  return true;
}
}

TEST(TestOrientation, InwardClosedSurfaceIsFoundAndOutwardIsNot)
{
  for (const Vec3f& centre : { Vec3f(0.f), Vec3f(3.e5f, -2.e6f, 40.f) })
  {
    const Scene inward = Sphere(centre, 2.f, kPi, true);
    const SurfaceOrientation found = findInwardSurfaces(inward, {});
    EXPECT_EQ(found.surfaces, 1u);
    ASSERT_EQ(found.inward.size(), 1u);
    EXPECT_EQ(found.inward[0].triangles.size(), inward.triangleCount());
    EXPECT_EQ(found.inward[0].vertices.size(), inward.vertexCount());
    EXPECT_EQ(found.againstWinding, 0u);
    EXPECT_TRUE(findInwardSurfaces(Sphere(centre, 2.f, kPi, false), {}).inward.empty());

    Scene flipped = inward;
    flipNormals(flipped, found.inward[0]);
    EXPECT_TRUE(NormalsEqual(flipped, inward, -1.f));
    EXPECT_TRUE(findInwardSurfaces(flipped, {}).inward.empty());
  }
}

TEST(TestOrientation, OnlyTheInwardOfTwoSurfacesIsFound)
{
  Scene s = Sphere(Vec3f(0.f), 1.f, kPi, false);
  const Scene second = Sphere(Vec3f(5.f, 0.f, 0.f), 1.f, kPi, true);
  const Index first = Index(s.vertexCount());
  for (std::size_t v = 0; v < second.vertexCount(); ++v)
  {
    s.positions.push_back(second.positions[v]);
    s.normals.push_back(second.normals[v]);
  }
  for (const Triangle& t : second.triangles)
  {
    s.triangles.push_back({ { t.v[0] + first, t.v[1] + first, t.v[2] + first } });
  }
  const SurfaceOrientation found = findInwardSurfaces(s, {});
  EXPECT_EQ(found.surfaces, 2u);
  ASSERT_EQ(found.inward.size(), 1u);
  EXPECT_EQ(found.inward[0].vertices.size(), second.vertexCount());
  EXPECT_EQ(found.inward[0].vertices.front(), first);
}

TEST(TestOrientation, VerticesSplitFromOnePointBelongToOneSurface)
{
  // Every vertex of the inward sphere duplicated per triangle (as splitting at sharp edges
  // does to a cube, or a triangle soup): the copies of a point are one through the point
  // ids, and where they lie at one position through that. Copies moved apart (by less than
  // the sphere notices) are one through the ids only: without them no edge is shared and
  // nothing is closed.
  const Scene welded = Sphere(Vec3f(0.f), 1.f, kPi, true, 8, 12);
  for (const bool apart : { false, true })
  {
    Scene split;
    std::vector<std::uint64_t> pointIds;
    for (const Triangle& t : welded.triangles)
    {
      Triangle copy;
      for (int k = 0; k < 3; ++k)
      {
        copy.v[k] = Index(split.positions.size());
        const float shift = apart ? 1e-5f * float(split.positions.size() % 7) : 0.f;
        split.positions.push_back(welded.positions[t.v[k]] + Vec3f(shift, 0.f, 0.f));
        split.normals.push_back(welded.normals[t.v[k]]);
        pointIds.push_back(t.v[k] * 7919u + 3u); // any ids, equal for copies of one point
      }
      split.triangles.push_back(copy);
    }
    EXPECT_EQ(findInwardSurfaces(split, {}).inward.empty(), apart) << apart;
    const SurfaceOrientation found = findInwardSurfaces(split, pointIds);
    EXPECT_EQ(found.surfaces, 1u) << apart;
    EXPECT_EQ(found.inward.size(), 1u) << apart;
  }
}

TEST(TestOrientation, SmallHolesStillCloseASurface)
{
  // Polar caps of 5 degrees cut out at both ends: border length^2 / area = 0.1.
  Scene s = Sphere(Vec3f(0.f), 1.f, kPi, true, 36, 32);
  Scene holed;
  holed.positions = s.positions;
  holed.normals = s.normals;
  const Index last = Index(s.vertexCount() - 1);
  for (const Triangle& t : s.triangles)
  {
    const bool pole = t.v[0] == 0 || t.v[1] == 0 || t.v[2] == 0 || t.v[0] == last ||
      t.v[1] == last || t.v[2] == last;
    if (!pole)
    {
      holed.triangles.push_back(t);
    }
  }
  EXPECT_EQ(findInwardSurfaces(holed, {}).inward.size(), 1u);
}

TEST(TestOrientation, OpenSurfacesHaveNoInside)
{
  for (const bool inward : { false, true })
  {
    for (const Scene& s : { Sphere(Vec3f(0.f), 1.f, 0.5f * kPi, inward),
           Sphere(Vec3f(0.f), 1.f, 0.7f * kPi, inward), Tube(inward) })
    {
      EXPECT_TRUE(findInwardSurfaces(s, {}).inward.empty()) << inward;
    }
  }
}

TEST(TestOrientation, ASeamOfRepeatedPointsStillClosesASurface)
{
  // An inward sphere whose first meridian is repeated: the triangles of its last segment use
  // copies of that meridian's points (a structured grid's surface that wraps around, an OBJ
  // file's vertices split by texture coordinates). Its points at one position are one, so
  // it is closed and found inward; without the copies it is the same sphere.
  const int segments = 32;
  Scene s = Sphere(Vec3f(0.f), 1.f, kPi, true, 24, segments);
  const std::size_t ringVertices = s.vertexCount() - 2;
  std::vector<Index> copyOf(s.vertexCount(), kInvalidIndex);
  for (Triangle& t : s.triangles)
  {
    const auto column = [&](Index v) { return v == 0 || v > ringVertices ? -1 : int((v - 1) % segments); };
    const bool last = column(t.v[0]) == segments - 1 || column(t.v[1]) == segments - 1 ||
      column(t.v[2]) == segments - 1;
    for (Index& v : t.v)
    {
      if (last && column(v) == 0)
      {
        if (copyOf[v] == kInvalidIndex)
        {
          copyOf[v] = Index(s.positions.size());
          s.positions.push_back(s.positions[v]);
          s.normals.push_back(s.normals[v]);
        }
        v = copyOf[v];
      }
    }
  }
  ASSERT_GT(s.vertexCount(), ringVertices + 2) << "the seam was repeated";
  const SurfaceOrientation found = findInwardSurfaces(s, {});
  ASSERT_EQ(found.inward.size(), 1u);
  EXPECT_EQ(found.inward[0].vertices.size(), s.vertexCount()) << "the copies belong to it";
}

TEST(TestOrientation, NormalsAgainstTheWindingAreCounted)
{
  Scene s = Sphere(Vec3f(0.f), 1.f, kPi, false);
  for (Triangle& t : s.triangles)
  {
    std::swap(t.v[1], t.v[2]); // winding inward, normals still outward
  }
  const SurfaceOrientation found = findInwardSurfaces(s, {});
  EXPECT_EQ(found.againstWinding, s.triangleCount());
  EXPECT_TRUE(found.inward.empty()); // the normals decide which side is the front

  // Slivers and specks have no side to disagree with: a triangle whose corners are a
  // rounding apart (vtkParametricTorus's seam) is not counted, whichever way it turns.
  Scene outward = Sphere(Vec3f(0.f), 1.f, kPi, false);
  const Index base = Index(outward.positions.size());
  const Vec3f at(1.f, 0.f, 0.f);
  for (const Vec3f& p : { at, at + Vec3f(0.f, 0.5f, 0.f), at + Vec3f(0.f, 0.25f, 1e-8f), // a sliver
         at, at + Vec3f(0.f, 1e-9f, 0.f), at + Vec3f(0.f, 0.f, 1e-9f) }) // a speck
  {
    outward.positions.push_back(p);
    outward.normals.push_back(Vec3f(1.f, 0.f, 0.f));
  }
  outward.triangles.push_back({ { base, base + 2, base + 1 } });
  outward.triangles.push_back({ { base + 3, base + 5, base + 4 } }); // facing -x: against
  EXPECT_EQ(findInwardSurfaces(outward, {}).againstWinding, 0u);
}

TEST(TestOrientation, NormalsSmoothedAcrossSharpEdgesAreMeasured)
{
  // A cube of 8 shared corners whose normals average its three faces (55 degrees from each,
  // as CAD exports write them): every corner is bent, all of the area. Split at its edges
  // (a normal per face) or a sphere's smooth normals: none.
  Scene cube;
  for (int i = 0; i < 8; ++i)
  {
    const Vec3f p(i & 1 ? 1.f : -1.f, i & 2 ? 1.f : -1.f, i & 4 ? 1.f : -1.f);
    cube.positions.push_back(p);
    cube.normals.push_back(normalize(p));
  }
  const Index faces[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 }, { 0, 4, 6, 2 },
    { 1, 3, 7, 5 } }; // each counter-clockwise seen from outside
  for (const auto& f : faces)
  {
    cube.triangles.push_back({ { f[0], f[1], f[2] } });
    cube.triangles.push_back({ { f[0], f[2], f[3] } });
  }
  cube.albedo.assign(8, Vec3f(0.5f));
  const SurfaceOrientation bent = findInwardSurfaces(cube, {});
  EXPECT_EQ(bent.againstWinding, 0u);
  EXPECT_TRUE(bent.inward.empty());
  EXPECT_EQ(bent.bentNormals, 8u);
  EXPECT_NEAR(bent.bentNormalArea, 1.0, 1e-9);

  MeshBuilder split;
  split.addBox({ -1.f, -1.f, -1.f }, { 1.f, 1.f, 1.f }, 2.f, Vec3f(0.5f));
  EXPECT_EQ(findInwardSurfaces(split.scene(), {}).bentNormals, 0u);
  Scene sphere = Sphere(Vec3f(0.f), 1.f, kPi, false);
  EXPECT_EQ(findInwardSurfaces(sphere, {}).bentNormals, 0u);
  // Normals as a transform that scaled the surface by 1e30 leaves them, 1e-30 long (their
  // squares underflow in float): measured by their direction all the same.
  for (Vec3f& n : sphere.normals)
  {
    n = n * 1e-30f;
  }
  EXPECT_EQ(findInwardSurfaces(sphere, {}).bentNormals, 0u);
}

TEST(TestOrientation, ALampInsideMakesARoomOfAnInwardSurface)
{
  Scene room = Sphere(Vec3f(10.f, 0.f, 0.f), 3.f, kPi, true);
  const InwardSurface surface = findInwardSurfaces(room, {}).inward.at(0);
  Light lamp;
  lamp.position = { 10.5f, 1.f, -2.f }; // inside
  room.lights = { lamp };
  EXPECT_TRUE(hasLightInside(room, surface));
  room.lights[0].position = { 10.f, 0.f, 3.5f }; // outside, just above the top
  EXPECT_FALSE(hasLightInside(room, surface));
  room.lights[0].position = { 12.4f, 2.4f, 0.f }; // in the bounds' corner, outside the sphere
  EXPECT_FALSE(hasLightInside(room, surface));
  room.lights[0].type = LightType::Directional; // from infinitely far: outside
  EXPECT_FALSE(hasLightInside(room, surface));

  // An emitting vertex inside (a lamp modelled as geometry), or the surface's own emission.
  room.lights.clear();
  room.positions.push_back({ 10.f, 0.f, 0.f });
  room.normals.push_back({ 0.f, 0.f, 1.f });
  room.emission.assign(room.vertexCount(), Vec3f(0.f));
  EXPECT_FALSE(hasLightInside(room, surface));
  room.emission.back() = Vec3f(1.f);
  EXPECT_TRUE(hasLightInside(room, surface));
  room.emission.back() = Vec3f(0.f);
  room.emission[surface.vertices[5]] = Vec3f(1.f);
  EXPECT_TRUE(hasLightInside(room, surface));
}

TEST(TestOrientation, LitOnlyFromBehind)
{
  Scene s = Sphere(Vec3f(0.f), 1.f, 0.5f * kPi, false); // a dome, normals up and out
  Light light;
  light.position = { 0.f, 0.f, 0.5f }; // under the dome
  s.lights = { light };
  EXPECT_TRUE(litOnlyFromBehind(s));
  s.lights[0].position = { 0.f, 0.f, 3.f };
  EXPECT_FALSE(litOnlyFromBehind(s));
  s.lights[0].position = { 0.f, 0.f, 0.5f };
  s.lights[0].intensity = Vec3f(0.f); // a black light lights no side
  EXPECT_FALSE(litOnlyFromBehind(s));
}

namespace
{
/// `builder`'s scene lit by a point light at `lamp`, solved on the CPU: the scene, its direct
/// light and the update's warnings.
struct Lit
{
  Scene scene;
  std::vector<Vec3f> direct;
  std::vector<std::string> warnings;
  std::string backend; ///< that solved it
  bool warned(const char* what) const
  {
    return std::any_of(warnings.begin(), warnings.end(), [what](const std::string& w) { return w.find(what) != std::string::npos; });
  }
};
Lit Solve(MeshBuilder& builder, const Vec3f& lamp, Method method = Method::Links, Backend backend = Backend::Cpu)
{
  Lit out;
  out.scene = builder.take();
  Light light;
  light.position = lamp;
  out.scene.lights = { light };
  SolverOptions o;
  o.method = method;
  o.backend = backend;
  o.raysPerVertex = 16;
  Solver solver;
  out.direct = solver.update(out.scene, o).direct;
  out.warnings = solver.stats().warnings;
  out.backend = solver.stats().backend;
  return out;
}

/// Three tiles of a map, the middle one wound the other way (GIS polygons of mixed
/// orientation), lit from above.
MeshBuilder Tiles()
{
  MeshBuilder tiles;
  for (int i = 0; i < 3; ++i)
  {
    const Vec3f origin(1.1f * float(i), 0.f, 0.f), x(1.f, 0.f, 0.f), y(0.f, 1.f, 0.f);
    i == 1 ? tiles.addQuadGrid(origin, y, x, 4, 4, Vec3f(0.5f)) : tiles.addQuadGrid(origin, x, y, 4, 4, Vec3f(0.5f));
  }
  return tiles;
}

/// The share of the light facing the fronts of `builder`'s scene, lit by a point light at
/// `lamp`, that reaches them (litShareOfFronts), and whether an update warned about it.
std::pair<float, bool> LitShareAndWarning(MeshBuilder& builder, const Vec3f& lamp)
{
  const Lit lit = Solve(builder, lamp);
  return { litShareOfFronts(lit.scene, lit.direct), lit.warned("Shadows block") };
}

/// The surfaces of `lit` lit only on their backs (litOnlyOnTheirBacks, with a tracer of its own).
LitOnTheirBacks BackLit(const Lit& lit)
{
  std::size_t surfaces = 0;
  const std::vector<Index> surfaceOf = surfaceLabels(lit.scene, surfaces);
  const std::unique_ptr<RayTracer> tracer = createCpuRayTracer();
  tracer->build(lit.scene.positions, lit.scene.triangles);
  return litOnlyOnTheirBacks(lit.scene, surfaceOf, surfaces, lit.direct, *tracer);
}
}

TEST(TestOrientation, FrontsInTheShadowOfTheirOwnSurfaceAreWarnedAbout)
{
  // A tube open at both ends has no inside to test (findInwardSurfaces never lists it), yet
  // wound inside out and lit from outside its fronts that face the light are its inside's far
  // wall, in the shadow of its near wall: the update says so. Wound outward it says nothing,
  // and neither does a one-sided plane lit from above with a box shadowing most of it.
  for (const bool inward : { false, true })
  {
    MeshBuilder b;
    b.addCylinder({ 0.f, 0.f, -1.f }, { 0.f, 0.f, 1.f }, 1.f, 48, 8, false, Vec3f(0.5f), {}, inward);
    const auto [share, warned] = LitShareAndWarning(b, { 3.f, 1.f, 0.5f });
    EXPECT_EQ(warned, inward) << (inward ? "inside out" : "outward") << ", lit share " << share;
    EXPECT_LT(inward ? share : 0.f, 0.05f);
    EXPECT_GT(inward ? 1.f : share, 0.9f); // outward nothing shadows the lit side
  }
  MeshBuilder b;
  b.addQuadGrid({ -2.f, -2.f, 0.f }, { 4.f, 0.f, 0.f }, { 0.f, 4.f, 0.f }, 32, 32, Vec3f(0.5f));
  b.addBox({ -1.9f, -1.9f, 0.1f }, { 1.9f, 1.9f, 0.3f }, 0.5f, Vec3f(0.5f)); // a roof over most of it
  const auto [share, warned] = LitShareAndWarning(b, { 0.f, 0.f, 3.f });
  EXPECT_GT(share, 0.05f) << "the roof's top is lit";
  EXPECT_FALSE(warned);
}

TEST(TestOrientation, SurfacesLitOnlyOnTheirBacksAmongLitOnesAreWarnedAbout)
{
  // Three tiles of a map under a light, the middle one wound the other way: it is lit only
  // on its back, and the update says so.
  MeshBuilder tiles = Tiles();
  const Lit map = Solve(tiles, { 1.6f, 0.5f, 3.f });
  const LitOnTheirBacks r = BackLit(map);
  EXPECT_EQ(r.surfaces, 1u);
  EXPECT_EQ(r.frontLit, 2u);
  EXPECT_EQ(r.triangles, map.scene.triangleCount() / 3);
  EXPECT_TRUE(map.warned("1 of 3 lit surfaces"));
  // A box whose faces are surfaces of their own (split at its edges), lit from one side: its
  // far faces face away from the light, but their backs look into the box. Also with two
  // triangles per face (vtkCubeSource's box), whose vertices all lie on its edges.
  for (const float cell : { 0.25f, 2.f })
  {
    MeshBuilder box;
    box.addBox({ -1.f, -1.f, -1.f }, { 1.f, 1.f, 1.f }, cell, Vec3f(0.5f));
    const Lit lit = Solve(box, { 4.f, 1.f, 2.f });
    std::size_t faces = 0;
    surfaceLabels(lit.scene, faces);
    EXPECT_EQ(faces, 6u) << cell;
    EXPECT_EQ(BackLit(lit).surfaces, 0u) << cell;
    EXPECT_FALSE(lit.warned("lit only on their backs")) << cell;
  }
}

TEST(TestOrientation, EveryGpuBackendChecksWhichSurfacesAreLitOnlyOnTheirBacks)
{
  // The check traces its shadow rays through the BVH of the backend that solved: on the GPU,
  // the device's.
  LINKGI_REQUIRE_CUDA_DEVICE();
  for (const Method method :
    { Method::Links, Method::InstantRadiosity, Method::ImplicitVisibility, Method::PhotonMapping })
  {
    MeshBuilder tiles = Tiles();
    const Lit map = Solve(tiles, { 1.6f, 0.5f, 3.f }, method, Backend::Cuda);
    EXPECT_EQ(map.backend, "cuda") << "method " << int(method);
    EXPECT_TRUE(map.warned("1 of 3 lit surfaces")) << "method " << int(method);
  }
}
