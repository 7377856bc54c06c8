// The photon map's searches and estimates, piece by piece (pm/PmTypes.h, pm/PmMath.h): the
// kd-tree's searches against brute force, an estimate's area on a thin part, and which
// estimate a gather hit reads. Whole updates are TestPhotonMapping.cpp's.
#include "SceneFixtures.h"

#include "methods/pm/PhotonMapping.h"
#include "methods/pm/PmTypes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

using namespace linkgi;

// The searches both backends run on the plain-data tree (PmTypes.h) find what a brute-force
// scan finds: the nearest, the k nearest by (distance, index) and every point within a
// radius, among the accepted points, on clustered points with duplicates and ties.
TEST(TestPhotonMapping, TreeSearchesEqualBruteForce)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::vector<Vec3f> points;
  for (int i = 0; i < 5000; ++i)
  {
    // A third on a plane and some repeated, as photons on a wall are.
    Vec3f p(u(rng), i % 3 == 0 ? 0.f : u(rng), u(rng));
    points.push_back(i % 97 == 1 ? points[i - 1] : p);
  }
  const pm::PointTree tree(points);
  const pm::PointTreeView view = tree.view();
  ASSERT_EQ(view.count, points.size());
  std::vector<pm::Neighbour> found, all;
  int rejectedSome = 0;
  for (int q = 0; q < 600; ++q)
  {
    const Vec3f x = q < 100 ? points[q * 7] : Vec3f(1.5f * u(rng), 1.5f * u(rng), 1.5f * u(rng));
    const Index parity = Index(q % 3);
    const auto accept = [&](Index i) { return i % 3 != parity; };
    const float maxD2 = q % 4 == 0 ? 0.01f : std::numeric_limits<float>::max();
    all.clear();
    for (Index i = 0; i < Index(points.size()); ++i)
    {
      const Vec3f d = points[i] - x;
      if (dot(d, d) <= maxD2 && accept(i))
      {
        all.push_back({ dot(d, d), i });
      }
    }
    std::sort(all.begin(), all.end(), pm::nearer);
    for (const std::uint32_t k : { 1u, 8u, 64u })
    {
      const std::size_t n = tree.nearest(x, k, maxD2, accept, found);
      ASSERT_EQ(n, std::min<std::size_t>(k, all.size())) << "query " << q << ", k " << k;
      for (std::size_t i = 0; i < n; ++i)
      {
        EXPECT_EQ(found[i].index, all[i].index) << "query " << q << ", k " << k << ", rank " << i;
      }
    }
    const Index flat = pm::nearestOne(view, x, maxD2, accept);
    if (all.empty())
    {
      EXPECT_EQ(flat, kInvalidIndex) << "query " << q;
      ++rejectedSome;
      continue;
    }
    EXPECT_EQ(flat, all[0].index) << "query " << q;
    // Every point within the 10th's distance, accepted or not.
    const float r2 = all[std::min<std::size_t>(9, all.size() - 1)].d2;
    std::size_t within = 0, expected = 0;
    pm::forEachWithin(view, x, r2, [&](Index, float d2) { within += d2 <= r2; });
    for (const Vec3f& p : points)
    {
      expected += dot(p - x, p - x) <= r2;
    }
    EXPECT_EQ(within, expected) << "query " << q;
  }
  EXPECT_GT(rejectedSome, 0); // the distance bound was exercised
  // An empty tree finds nothing.
  const std::vector<Vec3f> none;
  const pm::PointTree empty(none);
  EXPECT_EQ(pm::nearestOne(empty.view(), Vec3f(0.f), 1.f, [](Index) { return true; }), kInvalidIndex);
}

TEST(TestPhotonMapping, EstimatesDivideByTheSurfaceTheirPhotonsCanCover)
{
  // Photons spread evenly (stratified) over a strip 4 cm wide and 2 m long, each of the same flux: the
  // radiance an estimate in its middle must find is their total flux / the strip's area / pi.
  // Jensen's disc of the 64 nearest photons is far wider than the strip, and divides by all
  // of it; the area the mesh measures within the disc is the strip's band of it.
  MeshBuilder b;
  b.addQuadGrid({ -1.f, -0.02f, 0.f }, { 2.f, 0.f, 0.f }, { 0.f, 0.04f, 0.f }, 100, 2, Vec3f(0.5f));
  const Scene strip = b.take();
  const pm::SurfaceTree surface(strip);
  std::vector<Vec3f> positions, normals, flux;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> jitter(0.f, 1.f);
  const int n = 400; // stratified: 200 cells along, 2 across, one photon in each
  for (int i = 0; i < n; ++i)
  {
    positions.emplace_back(-1.f + 0.01f * (float(i / 2) + jitter(rng)), -0.02f + 0.02f * (float(i % 2) + jitter(rng)), 0.f);
    normals.emplace_back(0.f, 0.f, 1.f);
    flux.emplace_back(1e-3f);
  }
  const pm::PointTree tree(positions);
  const pm::PhotonsView photons{ tree.view(), normals.data(), flux.data() };
  const float expected = float(n) * 1e-3f / (2.f * 0.04f) / kPi;
  // The mean over the estimates at the photons of the strip's middle (each has the noise of
  // its 64 photons, 12%).
  std::vector<pm::Neighbour> heap(64);
  double measured = 0.0, disc = 0.0, radius = 0.0;
  int sites = 0;
  for (int i = 0; i < n; ++i)
  {
    if (std::abs(positions[i].x) < 0.6f)
    {
      float r2 = 0.f;
      measured += pm::siteRadiance(photons, surface.view(false), Index(i), 64, 1.f, heap.data(), r2).x;
      disc += pm::siteRadiance(photons, pm::SurfaceView{}, Index(i), 64, 1.f, heap.data(), r2).x;
      radius += std::sqrt(r2);
      ++sites;
    }
  }
  measured /= sites;
  disc /= sites;
  radius /= sites;
  std::printf("radiance on the strip %.4g over its band, %.4g over the disc (r = %.3g m), true %.4g\n", measured,
    disc, radius, expected);
  EXPECT_GT(radius, 0.1) << "the disc is not wider than the strip";
  EXPECT_NEAR(measured, expected, 0.1 * expected);
  EXPECT_LT(disc, 0.5 * expected) << "the disc alone does not darken the strip";
  // A surface as wide as the disc keeps it: the band's area is the disc's.
  MeshBuilder wide;
  wide.addQuadGrid({ -1.f, -1.f, 0.f }, { 2.f, 0.f, 0.f }, { 0.f, 2.f, 0.f }, 50, 50, Vec3f(0.5f));
  const pm::SurfaceTree plane(wide.take());
  EXPECT_NEAR(pm::photonArea(plane.view(false), Vec3f(0.f), Vec3f(0.f, 0.f, 1.f), 0.09f), kPi * 0.09f, 1e-5f);
  // Photons on the strip's back count its area only where backs take photons.
  const Vec3f down(0.f, 0.f, -1.f);
  EXPECT_EQ(pm::photonArea(surface.view(false), Vec3f(0.f), down, 0.09f), kPi * 0.09f);
  // The band: the disc (r = 0.3) between y = -0.02 and 0.02, the integral of its chord.
  const float band = 2.f * (0.02f * std::sqrt(0.09f - 0.0004f) + 0.09f * std::asin(0.02f / 0.3f));
  EXPECT_NEAR(pm::photonArea(surface.view(true), Vec3f(0.f), down, 0.09f), band, 1e-5f);
  // The same strip of eight large triangles (a CAD export's) is measured as finely.
  MeshBuilder coarse;
  coarse.addQuadGrid({ -1.f, -0.02f, 0.f }, { 2.f, 0.f, 0.f }, { 0.f, 0.04f, 0.f }, 4, 1, Vec3f(0.5f));
  const pm::SurfaceTree few(coarse.take());
  EXPECT_NEAR(pm::photonArea(few.view(false), Vec3f(0.f), Vec3f(0.f, 0.f, 1.f), 0.09f), band, 1e-5f);
}

TEST(TestPhotonMapping, TheAreaABallCutsFromATriangleIsExact)
{
  // Against counting the cells of a fine grid over the triangle that lie in the ball, for
  // random triangles and balls of every relation: inside, outside, crossing an edge or a
  // corner, the triangle's plane at any height in the ball.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (int trial = 0; trial < 60; ++trial)
  {
    const Vec3f a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng)), c(u(rng), u(rng), u(rng));
    const Vec3f q(0.5f * u(rng), 0.5f * u(rng), 0.5f * u(rng));
    const float r = 0.2f + 0.6f * std::abs(u(rng)), r2 = r * r;
    const int n = 400; // cells along each edge: n^2 triangles of the triangle's subdivision
    double inside = 0.0;
    for (int i = 0; i < n; ++i)
    {
      for (int j = 0; i + j < n; ++j)
      {
        for (int up = 0; up < (i + j + 1 < n ? 2 : 1); ++up)
        {
          const float s = (float(i) + (up ? 2.f : 1.f) / 3.f) / n, t = (float(j) + (up ? 2.f : 1.f) / 3.f) / n;
          const Vec3f p = a + (b - a) * s + (c - a) * t;
          inside += dot(p - q, p - q) <= r2 ? 1.0 : 0.0;
        }
      }
    }
    const double whole = 0.5 * double(length(cross(b - a, c - a)));
    const double counted = whole * inside / (double(n) * double(n));
    const float exact = pm::triangleAreaInBall(q, r2, a, b, c);
    EXPECT_NEAR(exact, counted, 0.01 * whole + 1e-6) << trial;
    EXPECT_NEAR(pm::triangleAreaInBall(q, r2, c, b, a), exact, 1e-5f * float(whole) + 1e-7f) << "either winding";
  }
}

TEST(TestPhotonMapping, SurfacePiecesAreBoundedAtAnyScaleAndShape)
{
  // A large face, or slivers a millionth as wide as long, are cut into at most
  // kSurfacePieces more pieces than triangles; a surface 1e-20 across, or one of needles of
  // almost no area (whose cuts would be too many at any length) keep their triangles whole;
  // the pieces' areas sum to the surface's.
  const auto check = [](const Scene& scene, bool cut) {
    const pm::SurfacePieces pieces = pm::surfacePieces(scene);
    double area = 0.0, whole = 0.0;
    for (float a : pieces.areas)
    {
      area += a;
    }
    for (const Triangle& t : scene.triangles)
    {
      whole += 0.5 * double(length(cross(scene.positions[t.v[1]] - scene.positions[t.v[0]],
                        scene.positions[t.v[2]] - scene.positions[t.v[0]])));
    }
    EXPECT_LE(pieces.areas.size(), scene.triangles.size() + pm::kSurfacePieces);
    EXPECT_EQ(pieces.areas.size() > scene.triangles.size(), cut);
    EXPECT_NEAR(area, whole, 1e-4 * whole);
    EXPECT_EQ(pieces.corners.size(), 3 * pieces.areas.size());
  };
  MeshBuilder face;
  face.addQuadGrid({ 0.f, 0.f, 0.f }, { 1.f, 0.f, 0.f }, { 0.f, 1.f, 0.f }, 1, 1, Vec3f(0.5f));
  check(face.scene(), true);
  Scene tiny = face.take();
  for (Vec3f& p : tiny.positions)
  {
    p = p * 1e-20f;
  }
  check(tiny, false);
  MeshBuilder slivers, needles;
  for (int i = 0; i < 64; ++i)
  {
    slivers.addQuadGrid({ 0.f, float(i), 0.f }, { 1.f, 0.f, 0.f }, { 0.f, 1e-6f, 0.f }, 1, 1, Vec3f(0.5f));
    needles.addQuadGrid({ 0.f, 0.f, float(i) }, { 1.f, 0.f, 0.f }, { 0.f, 1e-30f, 0.f }, 1, 1, Vec3f(0.5f));
  }
  check(slivers.scene(), true);
  check(needles.scene(), false);
}

TEST(TestPhotonMapping, EstimatesAtAContactDivideByTheSurfaceBesideIt)
{
  // A floor of two large triangles meeting a wall along x = 0 (the wall stands on the
  // floor's edge, facing +x): a disc on the floor at the wall's foot holds photons on half
  // of it, on the floor; at the floor's corner with a second wall, on a quarter of it.
  // Dividing by the whole disc darkened every point where two surfaces meet (a CAD case's
  // corners, a box's foot), whatever the photons' count.
  MeshBuilder b;
  b.addQuadGrid({ 0.f, -1.f, 0.f }, { 1.f, 0.f, 0.f }, { 0.f, 2.f, 0.f }, 1, 1, Vec3f(0.5f)); // the floor, +z
  b.addQuadGrid({ 0.f, -1.f, 0.f }, { 0.f, 2.f, 0.f }, { 0.f, 0.f, 1.f }, 1, 1, Vec3f(0.5f)); // a wall, +x
  b.addQuadGrid({ 0.f, -1.f, 0.f }, { 0.f, 0.f, 1.f }, { 1.f, 0.f, 0.f }, 1, 1, Vec3f(0.5f)); // a wall, +y
  const pm::SurfaceTree surface(b.take());
  const Vec3f up(0.f, 0.f, 1.f);
  const float r2 = 0.01f;
  EXPECT_NEAR(pm::photonArea(surface.view(false), Vec3f(0.f, 0.f, 0.f), up, r2), 0.5f * kPi * r2, 1e-6f);
  EXPECT_NEAR(pm::photonArea(surface.view(false), Vec3f(0.f, -1.f, 0.f), up, r2), 0.25f * kPi * r2, 1e-6f);
  EXPECT_NEAR(pm::photonArea(surface.view(false), Vec3f(0.5f, 0.f, 0.f), up, r2), kPi * r2, 1e-6f);
  // Off the surface by a third of the radius: the disc the ball cuts from the floor.
  EXPECT_NEAR(pm::photonArea(surface.view(false), Vec3f(0.5f, 0.f, 0.1f / 3.f), up, r2),
    kPi * (r2 - 0.01f / 9.f), 1e-6f);
}

TEST(TestPhotonMapping, GatherReadsTheEstimateOfItsOwnSurface)
{
  // A gather ray's hit reads the nearest radiance estimate that faces its way and lies near
  // its tangent plane, not a nearer one on another surface: the bright inside of a double
  // wall 1 cm behind, facing the same way, or a wall at right angles.
  const std::vector<Vec3f> sites = { { 0.f, 0.f, -0.01f }, { 0.05f, 0.f, 0.f }, { 0.01f, 0.f, 0.f },
    // a sphere of radius 1: an estimate 0.3 rad from the pole, and an inner shell 2 cm inside
    { std::sin(0.3f), 0.f, 10.f + std::cos(0.3f) }, { 0.f, 0.f, 10.98f } };
  const std::vector<Vec3f> normals = { { 0.f, 0.f, 1.f }, { 0.f, 0.f, 1.f }, { 1.f, 0.f, 0.f },
    { std::sin(0.3f), 0.f, std::cos(0.3f) }, { 0.f, 0.f, 1.f } };
  const std::vector<Vec3f> radiance = { Vec3f(10.f), Vec3f(1.f), Vec3f(5.f), Vec3f(2.f), Vec3f(10.f) };
  std::vector<float> radius2(sites.size(), 1.f); // the discs their photons came from
  const pm::PointTree tree(sites);
  pm::RadianceSitesView view;
  view.tree = tree.view();
  view.normals = normals.data();
  view.radiance = radiance.data();
  view.radius2 = radius2.data();
  const Vec3f up(0.f, 0.f, 1.f);
  EXPECT_EQ(pm::lookupRadiance(view, Vec3f(0.f), up), Vec3f(1.f)) << "the plane's own estimate";
  EXPECT_EQ(pm::lookupRadiance(view, Vec3f(0.f, 0.f, 11.f), up), Vec3f(2.f)) << "the sphere's own estimate";
  EXPECT_EQ(pm::lookupRadiance(view, Vec3f(0.f, 0.f, -0.01f), up), Vec3f(10.f)) << "the inner wall's own";
  // An estimate speaks for its photons' disc only: 5 cm from the plane's, whose photons lay
  // within 4 cm of it, nothing is known (as under an object resting on a lit floor).
  radius2[1] = 0.04f * 0.04f;
  EXPECT_EQ(pm::lookupRadiance(view, Vec3f(0.04f, 0.f, 0.f), up), Vec3f(1.f)) << "within its disc";
  EXPECT_EQ(pm::lookupRadiance(view, Vec3f(0.f), up), Vec3f(0.f)) << "beyond its disc";
  radius2[1] = 1.f;
  view.maxDistance2 = 0.04f * 0.04f; // only the other surfaces' estimates are this near
  EXPECT_EQ(pm::lookupRadiance(view, Vec3f(0.f), up), Vec3f(0.f)) << "none of its own within reach";
}
