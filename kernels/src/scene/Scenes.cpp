#include "linkgi/Scenes.h"

#include "linkgi/Error.h"
#include "scene/MeshBuilder.h"
#include "scene/ScenesCommon.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace linkgi
{
namespace scenes
{
int cells(float length, float cellSize)
{
  return std::max(1, int(std::ceil(length / cellSize - 1e-3f)));
}

Index addRect(MeshBuilder& b, const Vec3f& origin, const Vec3f& edgeU, const Vec3f& edgeV,
  float cellSize, const Vec3f& albedo, const Vec3f& emission)
{
  return b.addQuadGrid(origin, edgeU, edgeV, cells(length(edgeU), cellSize),
    cells(length(edgeV), cellSize), albedo, emission);
}

void addRoom(MeshBuilder& b, const Vec3f& min, const Vec3f& max, float cellSize,
  const Vec3f& floor, const Vec3f& ceiling, const std::array<Vec3f, 4>& walls)
{
  const Vec3f d = max - min;
  const Vec3f dx(d.x, 0.f, 0.f), dy(0.f, d.y, 0.f), dz(0.f, 0.f, d.z);
  // Edge order makes every cross(edgeU, edgeV) point into the room.
  addRect(b, min, dz, dx, cellSize, floor);
  addRect(b, Vec3f(min.x, max.y, min.z), dx, dz, cellSize, ceiling);
  addRect(b, min, dy, dz, cellSize, walls[0]);                          // x = min.x
  addRect(b, Vec3f(max.x, min.y, min.z), dz, dy, cellSize, walls[1]);   // x = max.x
  addRect(b, min, dx, dy, cellSize, walls[2]);                          // z = min.z
  addRect(b, Vec3f(min.x, min.y, max.z), dy, dx, cellSize, walls[3]);   // z = max.z
}

Index addBoxAt(MeshBuilder& b, const Vec3f& center, const Vec3f& size, float cellSize,
  const Vec3f& albedo, float yaw, const Vec3f& pivot)
{
  const Index first = b.addBox(center - size * 0.5f, center + size * 0.5f, cellSize, albedo);
  if (yaw != 0.f)
  {
    b.rotateY(first, pivot, yaw);
  }
  return first;
}

void addTable(MeshBuilder& b, const Vec3f& floorCenter, const Vec3f& size, float cellSize,
  const Vec3f& top, const Vec3f& legs, int legSegments)
{
  const float thickness = 0.04f, legRadius = 0.03f;
  const Vec3f c = floorCenter;
  addBoxAt(b, c + Vec3f(0.f, size.y - thickness * 0.5f, 0.f),
    Vec3f(size.x, thickness, size.z), cellSize, top);
  for (int k = 0; k < 4; ++k)
  {
    const float sx = (k & 1) ? 1.f : -1.f, sz = (k & 2) ? 1.f : -1.f;
    const Vec3f foot = c + Vec3f(sx * (size.x * 0.5f - 0.08f), 0.f, sz * (size.z * 0.5f - 0.08f));
    // No caps: the ends touch the floor and the table top and could never be seen.
    b.addCylinder(foot, foot + Vec3f(0.f, size.y - thickness, 0.f), legRadius, legSegments, 4,
      false, legs);
  }
}

void addChair(MeshBuilder& b, const Vec3f& floorCenter, float yaw, float cellSize,
  const Vec3f& seat, const Vec3f& frame)
{
  const Index first = b.vertexCount();
  const Vec3f c = floorCenter;
  const float h = 0.45f, w = 0.44f, leg = 0.035f;
  addBoxAt(b, c + Vec3f(0.f, h, 0.f), Vec3f(w, 0.05f, w), cellSize, seat);
  addBoxAt(b, c + Vec3f(0.f, h + 0.3f, -w * 0.5f + 0.025f), Vec3f(w, 0.45f, 0.05f), cellSize,
    seat);
  for (int k = 0; k < 4; ++k)
  {
    const float sx = (k & 1) ? 1.f : -1.f, sz = (k & 2) ? 1.f : -1.f;
    const Vec3f foot = c + Vec3f(sx * (w * 0.5f - leg), (h - 0.025f) * 0.5f, sz * (w * 0.5f - leg));
    addBoxAt(b, foot, Vec3f(leg, h - 0.025f, leg), cellSize, frame);
  }
  b.rotateY(first, c, yaw);
}

void addShade(MeshBuilder& b, const Vec3f& bottom, float height, float r0, float r1,
  int segments, const Vec3f& albedo)
{
  // The bulb sits a few centimetres from the inner wall, where irradiance changes fast with
  // height: the walls need rows every ~2 cm, or vertex interpolation loses (measured against
  // the reference) a fifth of the light bouncing inside the shade. Flat rims close the 5 mm
  // gap; small tori there were too coarse for the bright light right next to them.
  const Vec3f top = bottom + Vec3f(0.f, height, 0.f);
  const int stacks = std::max(4, int(std::lround(height / 0.02f)));
  b.addCone(bottom, top, r0, r1, segments, stacks, false, albedo);
  b.addCone(bottom, top, r0 - 0.005f, r1 - 0.005f, segments, stacks, false, albedo, Vec3f(), true);
  b.addRevolution(bottom, Vec3f(0.f, 1.f, 0.f), { { r0 - 0.005f, 0.f }, { r0, 0.f } }, segments,
    albedo); // faces down
  b.addRevolution(top, Vec3f(0.f, 1.f, 0.f), { { r1, 0.f }, { r1 - 0.005f, 0.f } }, segments,
    albedo); // faces up
}

Light pointLight(const Vec3f& position, const Vec3f& intensity)
{
  Light light;
  light.type = LightType::Point;
  light.position = position;
  light.intensity = intensity;
  return light;
}
}

using namespace scenes;

namespace
{
const Vec3f kCornellWhite(0.725f, 0.71f, 0.68f);
const Vec3f kCornellRed(0.63f, 0.065f, 0.05f);
const Vec3f kCornellGreen(0.14f, 0.45f, 0.091f);

/// Quad p0..p3 turned so that its normal points away from `inside` (block faces).
void addQuadAwayFrom(MeshBuilder& b, const Vec3f& inside, Vec3f p0, Vec3f p1, Vec3f p2, Vec3f p3,
  float cellSize, const Vec3f& albedo, const Vec3f& emission = {})
{
  if (dot(cross(p2 - p0, p3 - p1), (p0 + p1 + p2 + p3) * 0.25f - inside) < 0.f)
  {
    std::swap(p1, p3);
  }
  b.addQuad(p0, p1, p2, p3, cells(length(p1 - p0), cellSize), cells(length(p3 - p0), cellSize),
    albedo, emission);
}

/// The Cornell box, from the published "Cornell Box Data" (graphics.cornell.edu), converted
/// from millimetres to metres so that light intensities are in ordinary units. The front
/// (z = 0, the camera side, camera at (0.278, 0.273, -0.8) looking +z) is open.
Scene makeCornell(const SceneParams& params)
{
  MeshBuilder b;
  const float mm = 0.001f, cell = params.cornellCell > 0.f ? params.cornellCell : 0.016f;
  const auto P = [&](float x, float y, float z) { return Vec3f(x, y, z) * mm; };
  const Vec3f room = P(278.f, 274.4f, 279.6f);
  // Walls face the room's centre: "away from" a point mirrored far behind each wall.
  const auto wall = [&](Vec3f p0, Vec3f p1, Vec3f p2, Vec3f p3, const Vec3f& albedo)
  {
    const Vec3f c = (p0 + p1 + p2 + p3) * 0.25f;
    addQuadAwayFrom(b, c + (c - room), p0, p1, p2, p3, cell, albedo);
  };
  wall(P(552.8f, 0, 0), P(0, 0, 0), P(0, 0, 559.2f), P(549.6f, 0, 559.2f), kCornellWhite);
  wall(P(549.6f, 0, 559.2f), P(0, 0, 559.2f), P(0, 548.8f, 559.2f), P(556, 548.8f, 559.2f),
    kCornellWhite);
  wall(P(0, 0, 559.2f), P(0, 0, 0), P(0, 548.8f, 0), P(0, 548.8f, 559.2f), kCornellGreen);
  wall(P(552.8f, 0, 0), P(549.6f, 0, 559.2f), P(556, 548.8f, 559.2f), P(556, 548.8f, 0),
    kCornellRed);

  // Ceiling (556 x 559.2) with the 130 x 105 opening of the light, as one grid whose lines
  // pass through the opening's edges, so that cells never straddle it.
  const float ceilY = 548.8f * mm;
  const std::array<float, 4> xs = { 0.f, 213.f * mm, 343.f * mm, 556.f * mm };
  const std::array<float, 4> zs = { 0.f, 227.f * mm, 332.f * mm, 559.2f * mm };
  std::vector<float> gx, gz;
  for (int k = 0; k < 3; ++k)
  {
    const int nx = cells(xs[k + 1] - xs[k], cell), nz = cells(zs[k + 1] - zs[k], cell);
    for (int i = 0; i < nx; ++i)
    {
      gx.push_back(xs[k] + (xs[k + 1] - xs[k]) * float(i) / float(nx));
    }
    for (int i = 0; i < nz; ++i)
    {
      gz.push_back(zs[k] + (zs[k + 1] - zs[k]) * float(i) / float(nz));
    }
  }
  gx.push_back(xs[3]);
  gz.push_back(zs[3]);
  const auto inOpening = [&](std::size_t i, std::size_t j)
  { return gx[i] >= xs[1] && gx[i + 1] <= xs[2] && gz[j] >= zs[1] && gz[j + 1] <= zs[2]; };
  // Grid vertices are created on first use, so the opening has no unused vertices.
  std::vector<Index> id(gx.size() * gz.size(), kInvalidIndex);
  const auto vertex = [&](std::size_t i, std::size_t j)
  {
    Index& v = id[j * gx.size() + i];
    if (v == kInvalidIndex)
    {
      v = b.addVertex(Vec3f(gx[i], ceilY, gz[j]), Vec3f(0.f, -1.f, 0.f), kCornellWhite);
    }
    return v;
  };
  for (std::size_t j = 0; j + 1 < gz.size(); ++j)
  {
    for (std::size_t i = 0; i + 1 < gx.size(); ++i)
    {
      if (inOpening(i, j))
      {
        continue;
      }
      // cross(+x, +z) = -y: counter-clockwise seen from below.
      b.addTriangle(vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1));
      b.addTriangle(vertex(i, j), vertex(i + 1, j + 1), vertex(i, j + 1));
    }
  }
  // The light's patch fills the opening (its own elements: it may emit, the ceiling never).
  const Vec3f lightCenter = P(278.f, 548.8f, 279.5f);
  const Vec3f lightRadiance(17.f, 12.f, 4.f);
  addQuadAwayFrom(b, lightCenter + Vec3f(0.f, 1.f, 0.f), P(343, 548.8f, 227),
    P(343, 548.8f, 332), P(213, 548.8f, 332), P(213, 548.8f, 227), cell, kCornellWhite,
    params.cornellAreaLight ? lightRadiance : Vec3f());

  const auto block = [&](const std::array<Vec3f, 4>& top)
  {
    Vec3f c(0.f);
    for (const Vec3f& p : top)
    {
      c += p * 0.25f;
    }
    c.y *= 0.5f;
    addQuadAwayFrom(b, c, top[0], top[1], top[2], top[3], cell, kCornellWhite);
    for (int k = 0; k < 4; ++k)
    {
      const Vec3f a = top[std::size_t(k)], d = top[std::size_t((k + 1) % 4)];
      addQuadAwayFrom(b, c, Vec3f(a.x, 0.f, a.z), Vec3f(d.x, 0.f, d.z), d, a, cell,
        kCornellWhite);
    }
  };
  block({ P(130, 165, 65), P(82, 165, 225), P(240, 165, 272), P(290, 165, 114) });
  block({ P(423, 330, 247), P(265, 330, 296), P(314, 330, 456), P(472, 330, 406) });

  Scene scene = b.take();
  if (!params.cornellAreaLight)
  {
    // About the area light's colour, 10 cm below the opening: closer, the ceiling would get
    // a grazing 1/r^3 hot spot around the light that 256 rays per vertex cannot resolve.
    // Floor irradiance ~ (3.9, 2.7, 0.9).
    scene.lights.push_back(
      pointLight(lightCenter - Vec3f(0.f, 0.1f, 0.f), lightRadiance * 0.05f));
  }
  return scene;
}

/// Inside of a closed sphere: every element sees only the sphere, so the exact answer is the
/// geometric series L = Le / (1 - rho) = 2 everywhere.
Scene makeFurnace()
{
  MeshBuilder b;
  b.addIcosphere(Vec3f(0.f), 1.f, 4, Vec3f(0.5f), Vec3f(1.f), true); // 2562 vertices
  return b.take();
}

/// A room corner with a table and a lamp whose red shade colours the light around it.
Scene makeColorLamp()
{
  MeshBuilder b;
  const float cell = 0.24f;
  const Vec3f white(0.75f), floor(0.55f, 0.42f, 0.3f);
  const Vec3f blue(0.3f, 0.45f, 0.75f), yellow(0.8f, 0.7f, 0.3f), shade(0.85f, 0.22f, 0.1f);
  // Floor and two walls meeting in the corner at the origin; the other sides stay open.
  addRect(b, Vec3f(0.f), Vec3f(0.f, 0.f, 3.f), Vec3f(3.f, 0.f, 0.f), cell, floor);
  addRect(b, Vec3f(0.f), Vec3f(3.f, 0.f, 0.f), Vec3f(0.f, 2.5f, 0.f), cell, blue);
  addRect(b, Vec3f(0.f), Vec3f(0.f, 2.5f, 0.f), Vec3f(0.f, 0.f, 3.f), cell, yellow);

  const Vec3f table(0.9f, 0.f, 0.75f);
  addTable(b, table, Vec3f(1.1f, 0.72f, 0.7f), 0.2f, Vec3f(0.6f, 0.45f, 0.3f), white * 0.5f, 8);
  // Lamp: base, stem, and a conical shade open at both ends.
  const Vec3f base = table + Vec3f(0.f, 0.72f, 0.f);
  b.addCylinder(base, base + Vec3f(0.f, 0.03f, 0.f), 0.1f, 16, 1, true, Vec3f(0.3f));
  b.addCylinder(base + Vec3f(0.f, 0.03f, 0.f), base + Vec3f(0.f, 0.35f, 0.f), 0.012f, 8, 3,
    false, Vec3f(0.6f));
  addShade(b, base + Vec3f(0.f, 0.28f, 0.f), 0.24f, 0.2f, 0.11f, 22, shade);

  Scene scene = b.take();
  scene.lights.push_back(pointLight(base + Vec3f(0.f, 0.4f, 0.f), Vec3f(2.5f, 2.3f, 2.f)));
  return scene;
}

/// Torso profile: key sections (height, half width, half depth) in metres, bottom to top.
struct Section
{
  float y, wx, wz;
};

Section lerp(const Section& a, const Section& b, float t)
{
  return { a.y + (b.y - a.y) * t, a.wx + (b.wx - a.wx) * t, a.wz + (b.wz - a.wz) * t };
}

/// Catmull-Rom through the key sections, resampled by arc length so that rows of vertices are
/// evenly spaced along the body (a uniform spline parameter would crowd the neck).
std::vector<Section> torsoProfile(std::size_t samples)
{
  const std::vector<Section> keys = { { 0.f, 0.f, 0.f }, { 0.01f, 0.13f, 0.09f },
    { 0.05f, 0.16f, 0.11f }, { 0.14f, 0.165f, 0.115f }, { 0.27f, 0.13f, 0.095f },
    { 0.40f, 0.155f, 0.11f }, { 0.50f, 0.175f, 0.11f }, { 0.56f, 0.19f, 0.10f },
    { 0.60f, 0.15f, 0.08f }, { 0.625f, 0.06f, 0.055f }, { 0.68f, 0.045f, 0.048f },
    { 0.73f, 0.07f, 0.08f }, { 0.80f, 0.08f, 0.09f }, { 0.855f, 0.065f, 0.075f },
    { 0.877f, 0.035f, 0.04f }, { 0.885f, 0.f, 0.f } };
  const auto key = [&](int i) { return keys[std::size_t(std::clamp(i, 0, int(keys.size()) - 1))]; };
  std::vector<Section> dense;
  const int perSegment = 64;
  for (int i = 0; i + 1 < int(keys.size()); ++i)
  {
    const Section p0 = key(i - 1), p1 = key(i), p2 = key(i + 1), p3 = key(i + 2);
    for (int s = 0; s < perSegment; ++s)
    {
      const float t = float(s) / float(perSegment), t2 = t * t, t3 = t2 * t;
      const auto cr = [&](float a, float b, float c, float d)
      {
        return 0.5f * (2.f * b + (c - a) * t + (2.f * a - 5.f * b + 4.f * c - d) * t2 +
                        (3.f * b - a - 3.f * c + d) * t3);
      };
      dense.push_back({ cr(p0.y, p1.y, p2.y, p3.y), std::max(0.f, cr(p0.wx, p1.wx, p2.wx, p3.wx)),
        std::max(0.f, cr(p0.wz, p1.wz, p2.wz, p3.wz)) });
    }
  }
  dense.push_back(keys.back());
  std::vector<float> arc(dense.size(), 0.f);
  for (std::size_t i = 1; i < dense.size(); ++i)
  {
    const float dr = 0.5f * (dense[i].wx + dense[i].wz - dense[i - 1].wx - dense[i - 1].wz);
    arc[i] = arc[i - 1] + std::hypot(dr, dense[i].y - dense[i - 1].y);
  }
  std::vector<Section> out(samples + 1);
  std::size_t k = 0;
  for (std::size_t j = 0; j <= samples; ++j)
  {
    const float target = arc.back() * float(j) / float(samples);
    while (k + 2 < arc.size() && arc[k + 1] < target)
    {
      ++k;
    }
    const float t = std::clamp((target - arc[k]) / std::max(arc[k + 1] - arc[k], 1e-9f), 0.f, 1.f);
    out[j] = lerp(dense[k], dense[k + 1], t);
  }
  out.front() = keys.front();
  out.back() = keys.back();
  return out;
}

/// A mannequin-like torso with neck and head on a plinth, on a floor. `deformation` bends the
/// body forward (+z) and twists it about its vertical axis, both growing with height; it moves
/// vertices and normals only.
Scene makeTorso(float deformation)
{
  MeshBuilder b;
  const Vec3f white(0.75f), plinth(0.45f, 0.42f, 0.4f), skin(0.8f, 0.6f, 0.5f);
  addRect(b, Vec3f(-2.f, 0.f, -2.f), Vec3f(0.f, 0.f, 4.f), Vec3f(4.f, 0.f, 0.f), 0.12f, white);
  const float baseY = 0.8f;
  b.addBox(Vec3f(-0.25f, 0.f, -0.25f), Vec3f(0.25f, baseY, 0.25f), 0.1f, plinth);

  const int rows = 71, segments = 80;
  const std::vector<Section> profile = torsoProfile(rows);
  const float height = profile.back().y;
  const Index first = b.addSurface(
    [&](float u, float v)
    {
      const Section& s = profile[std::size_t(std::lround(v * float(rows)))];
      const float phi = 2.f * kPi * u;
      // (sin, cos) order: counter-clockwise seen from +Y, so the normals face outward.
      return Vec3f(s.wx * std::sin(phi), baseY + s.y, s.wz * std::cos(phi));
    },
    segments, rows, SurfaceTopology::closed(), skin);

  if (deformation != 0.f)
  {
    // The spine (the Y axis) bends forward, towards +z, to the angle theta(s) = B (s / H)^2 at
    // height s, so the waist and chest bend and the hips stay put; cross-sections stay rigid
    // and perpendicular to the spine, so nothing is stretched along it (rotating each point
    // about one pivot instead would stretch the head by half). Before bending, the body
    // twists about its own axis by an angle growing linearly with height.
    const float bend = 0.8f * deformation, twist = 0.7f * deformation;
    const auto theta = [&](float s) { return bend * (s / height) * (s / height); };
    b.deform(first,
      [&](const Vec3f& p)
      {
        const float s = p.y - baseY, tw = twist * s / height;
        const float x = p.x * std::cos(tw) + p.z * std::sin(tw);
        const float z = -p.x * std::sin(tw) + p.z * std::cos(tw);
        // Spine point: integral of (cos theta, sin theta) over [0, s], Simpson's rule with a
        // fixed number of intervals so that the result is smooth in s.
        const int n = 32;
        float sy = 0.f, sz = 0.f;
        for (int k = 0; k <= n; ++k)
        {
          const float w = (k == 0 || k == n) ? 1.f : (k % 2 ? 4.f : 2.f);
          const float a = theta(s * float(k) / float(n));
          sy += w * std::cos(a);
          sz += w * std::sin(a);
        }
        sy *= s / (3.f * float(n));
        sz *= s / (3.f * float(n));
        const float a = theta(s);
        return Vec3f(x, baseY + sy - z * std::sin(a), sz + z * std::cos(a));
      });
  }
  Scene scene = b.take();
  scene.lights.push_back(pointLight(Vec3f(1.2f, 2.6f, 1.8f), Vec3f(14.f, 13.f, 12.f)));
  return scene;
}

/// Every triangle from `first` on gets `material` (the ones before stay diffuse).
void setMaterial(Scene& scene, std::size_t first, MaterialType material, float ior = 1.5f)
{
  scene.triangleMaterials.resize(scene.triangles.size(), MaterialType::Diffuse);
  scene.triangleIor.resize(scene.triangles.size(), 1.5f);
  for (std::size_t t = first; t < scene.triangles.size(); ++t)
  {
    scene.triangleMaterials[t] = material;
    scene.triangleIor[t] = ior;
  }
}

/// Caustics: a glass ball (radius 0.35, index 1.5) 0.6 above a finely tessellated white
/// floor (2 x 2, 100 x 100 cells, 2 cm apart), a point light 1.4 above the ball's centre: the
/// ball focuses the light into a bright spot under it, inside its shadow, and a mirror band
/// around it throws a second, ring-shaped caustic onto the floor inside it.
Scene makeCaustics()
{
  MeshBuilder b;
  b.addQuadGrid(Vec3f(-1.f, 0.f, -1.f), Vec3f(0.f, 0.f, 2.f), Vec3f(2.f, 0.f, 0.f), 100, 100, Vec3f(0.8f));
  const std::size_t ball = b.scene().triangles.size();
  b.addIcosphere(Vec3f(0.f, 0.6f, 0.f), 0.35f, 4, Vec3f(0.8f));
  const std::size_t ring = b.scene().triangles.size();
  // A mirror band: the inside of a cylinder of radius 0.55 about the ball, 0.15 high.
  b.addCylinder(Vec3f(0.f, 0.f, 0.f), Vec3f(0.f, 0.15f, 0.f), 0.55f, 48, 2, false, Vec3f(0.8f), Vec3f(), true);
  Scene scene = b.take();
  setMaterial(scene, ball, MaterialType::Glass, 1.5f);
  setMaterial(scene, ring, MaterialType::Mirror);
  scene.lights.push_back(pointLight(Vec3f(0.f, 2.0f, 0.f), Vec3f(3.f)));
  return scene;
}

/// The Cornell box with a glass ball (radius 8 cm) on the short block.
Scene makeCornellGlass(const SceneParams& params)
{
  Scene scene = makeCornell(params);
  const std::size_t ball = scene.triangles.size();
  MeshBuilder b(std::move(scene));
  b.addIcosphere(Vec3f(0.186f, 0.165f + 0.08f, 0.169f), 0.08f, 3, Vec3f(0.8f));
  scene = b.take();
  setMaterial(scene, ball, MaterialType::Glass, 1.5f);
  return scene;
}

struct Entry
{
  const char* name;
  Scene (*make)(const SceneParams&);
};

const Entry kScenes[] = {
  { "furnace", [](const SceneParams&) { return makeFurnace(); } },
  { "colorlamp", [](const SceneParams&) { return makeColorLamp(); } },
  { "torso", [](const SceneParams& p) { return makeTorso(p.deformation); } },
  { "cornell", [](const SceneParams& p) { return makeCornell(p); } },
  { "tearoom", [](const SceneParams&) { return makeTearoom(); } },
  { "iphi", [](const SceneParams&) { return makeIphi(); } },
  { "conference", [](const SceneParams&) { return makeConference(); } },
  { "caustics", [](const SceneParams&) { return makeCaustics(); } },
  { "cornell-glass", [](const SceneParams& p) { return makeCornellGlass(p); } },
};
}

std::vector<std::string> standardSceneNames()
{
  std::vector<std::string> names;
  for (const Entry& e : kScenes)
  {
    names.emplace_back(e.name);
  }
  return names;
}

Scene makeStandardScene(const std::string& name, const SceneParams& params)
{
  for (const Entry& e : kScenes)
  {
    if (name == e.name)
    {
      return e.make(params);
    }
  }
  std::string valid;
  for (const Entry& e : kScenes)
  {
    valid += std::string(valid.empty() ? "" : ", ") + e.name;
  }
  throw Error("Unknown standard scene '" + name + "'; valid names are: " + valid + ".");
}
}
