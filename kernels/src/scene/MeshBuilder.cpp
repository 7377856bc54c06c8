#include "scene/MeshBuilder.h"

#include "linkgi/Error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace linkgi
{
namespace
{
/// Right-handed basis (e1, e2, axis): a point moving from e1 towards e2 turns counter-clockwise
/// seen from +axis, so d/dphi x axis points away from the axis (outward faces).
struct RingBasis
{
  Vec3f e1, e2, axis;

  explicit RingBasis(const Vec3f& direction)
  {
    axis = normalize(direction);
    const Frame f = Frame::fromNormal(axis);
    e1 = f.t;
    e2 = cross(axis, e1);
  }
  Vec3f ring(float u) const
  {
    const float phi = 2.f * kPi * u;
    return e1 * std::cos(phi) + e2 * std::sin(phi);
  }
};

int atLeast(int n, int minimum, const char* what)
{
  if (n < minimum)
  {
    throw Error(std::string("MeshBuilder: ") + what + " must be at least " +
      std::to_string(minimum) + ", got " + std::to_string(n) + ".");
  }
  return n;
}
}

Scene MeshBuilder::take()
{
  Scene out = std::move(target);
  target = Scene{};
  return out;
}

Index MeshBuilder::addVertex(
  const Vec3f& position, const Vec3f& normal, const Vec3f& albedo, const Vec3f& emission)
{
  const Index index = vertexCount();
  target.positions.push_back(position);
  target.normals.push_back(normal);
  target.albedo.push_back(albedo);
  target.emission.push_back(emission);
  return index;
}

void MeshBuilder::addTriangle(Index a, Index b, Index c)
{
  target.triangles.push_back(Triangle{ { a, b, c } });
}

Index MeshBuilder::addQuadGrid(const Vec3f& origin, const Vec3f& edgeU, const Vec3f& edgeV,
  int nu, int nv, const Vec3f& albedo, const Vec3f& emission)
{
  return addQuad(origin, origin + edgeU, origin + edgeU + edgeV, origin + edgeV, nu, nv, albedo,
    emission);
}

Index MeshBuilder::addQuad(const Vec3f& p0, const Vec3f& p1, const Vec3f& p2, const Vec3f& p3,
  int nu, int nv, const Vec3f& albedo, const Vec3f& emission)
{
  atLeast(nu, 1, "quad cells along u");
  atLeast(nv, 1, "quad cells along v");
  // The diagonals' cross product is the exact normal of a planar quad and a fair average of
  // a slightly warped one (the published Cornell box walls are not quite planar).
  const Vec3f n = normalize(cross(p2 - p0, p3 - p1));
  const Index first = vertexCount();
  for (int j = 0; j <= nv; ++j)
  {
    const float t = float(j) / float(nv);
    for (int i = 0; i <= nu; ++i)
    {
      const float s = float(i) / float(nu);
      const Vec3f p = (p0 * (1.f - s) + p1 * s) * (1.f - t) + (p3 * (1.f - s) + p2 * s) * t;
      addVertex(p, n, albedo, emission);
    }
  }
  const auto at = [&](int i, int j) { return first + Index(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      addTriangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      addTriangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return first;
}

Index MeshBuilder::addBox(const Vec3f& min, const Vec3f& max, float cellSize,
  const Vec3f& albedo, bool inward, const Vec3f& emission)
{
  if (!(cellSize > 0.f))
  {
    throw Error("MeshBuilder: box cell size must be positive.");
  }
  const Vec3f d = max - min;
  const auto cells = [&](float length)
  { return std::max(1, int(std::ceil(length / cellSize - 1e-4f))); };
  const Vec3f dx(d.x, 0.f, 0.f), dy(0.f, d.y, 0.f), dz(0.f, 0.f, d.z);
  // Each face as origin and two edges whose cross product points out of the box.
  struct Face
  {
    Vec3f origin, u, v;
  };
  const std::array<Face, 6> faces = { {
    { min, dz, dy },                                   // -X
    { Vec3f(max.x, min.y, min.z), dy, dz },            // +X
    { min, dx, dz },                                   // -Y
    { Vec3f(min.x, max.y, min.z), dz, dx },            // +Y
    { min, dy, dx },                                   // -Z
    { Vec3f(min.x, min.y, max.z), dx, dy },            // +Z
  } };
  const Index first = vertexCount();
  for (const Face& f : faces)
  {
    const Vec3f u = inward ? f.v : f.u;
    const Vec3f v = inward ? f.u : f.v;
    addQuadGrid(f.origin, u, v, cells(length(u)), cells(length(v)), albedo, emission);
  }
  return first;
}

Index MeshBuilder::addDisk(const Vec3f& center, const Vec3f& normal, float radius, int segments,
  int rings, const Vec3f& albedo, const Vec3f& emission)
{
  const RingBasis basis(normal);
  // v runs from the rim to the centre so that cross(d/du, d/dv) is +normal.
  return addGrid([&](float u, float v) { return center + basis.ring(u) * (radius * (1.f - v)); },
    segments, rings, { true, false, false, true }, albedo, emission, false);
}

Index MeshBuilder::addSphere(const Vec3f& center, float radius, int rings, int segments,
  const Vec3f& albedo, const Vec3f& emission, bool inward)
{
  atLeast(rings, 2, "sphere rings");
  std::vector<std::pair<float, float>> profile;
  for (int j = 0; j <= rings; ++j)
  {
    const float theta = kPi * (float(j) / float(rings) - 0.5f);
    profile.emplace_back(j == 0 || j == rings ? 0.f : radius * std::cos(theta),
      radius * std::sin(theta));
  }
  return addRevolution(center, Vec3f(0.f, 1.f, 0.f), profile, segments, albedo, emission, inward);
}

Index MeshBuilder::addIcosphere(const Vec3f& center, float radius, int level, const Vec3f& albedo,
  const Vec3f& emission, bool inward)
{
  atLeast(level, 0, "icosphere level");
  const float t = (1.f + std::sqrt(5.f)) / 2.f;
  std::vector<Vec3f> points = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 },
    { 0, -1, t }, { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 },
    { -t, 0, -1 }, { -t, 0, 1 } };
  for (Vec3f& p : points)
  {
    p = normalize(p);
  }
  std::vector<std::array<Index, 3>> faces = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 },
    { 0, 7, 10 }, { 0, 10, 11 }, { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 },
    { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 },
    { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
  for (int l = 0; l < level; ++l)
  {
    // Edge midpoints are shared by the two faces of the edge, so the sphere stays closed.
    std::map<std::pair<Index, Index>, Index> midpoints;
    const auto midpoint = [&](Index a, Index b)
    {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto found = midpoints.find(key);
      if (found != midpoints.end())
      {
        return found->second;
      }
      points.push_back(normalize(points[a] + points[b]));
      const Index m = Index(points.size() - 1);
      midpoints.emplace(key, m);
      return m;
    };
    std::vector<std::array<Index, 3>> refined;
    refined.reserve(faces.size() * 4);
    for (const auto& f : faces)
    {
      const Index ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
      refined.push_back({ f[0], ab, ca });
      refined.push_back({ f[1], bc, ab });
      refined.push_back({ f[2], ca, bc });
      refined.push_back({ ab, bc, ca });
    }
    faces.swap(refined);
  }
  const float side = inward ? -1.f : 1.f;
  const Index first = vertexCount();
  for (const Vec3f& p : points)
  {
    addVertex(center + p * radius, p * side, albedo, emission);
  }
  for (const auto& f : faces)
  {
    // Orient each face by its own geometry rather than trusting the table's winding.
    const Vec3f n = cross(points[f[1]] - points[f[0]], points[f[2]] - points[f[0]]);
    const bool outward = dot(n, points[f[0]] + points[f[1]] + points[f[2]]) > 0.f;
    if (outward != inward)
    {
      addTriangle(first + f[0], first + f[1], first + f[2]);
    }
    else
    {
      addTriangle(first + f[0], first + f[2], first + f[1]);
    }
  }
  return first;
}

Index MeshBuilder::addCone(const Vec3f& base, const Vec3f& top, float baseRadius,
  float topRadius, int segments, int stacks, bool caps, const Vec3f& albedo,
  const Vec3f& emission, bool inward)
{
  const Vec3f axis = top - base;
  const RingBasis basis(axis);
  const SurfaceTopology topology{ true, false, baseRadius <= 0.f, topRadius <= 0.f };
  const Index first = addGrid(
    [&](float u, float v)
    { return base + axis * v + basis.ring(u) * (baseRadius + (topRadius - baseRadius) * v); },
    segments, stacks, topology, albedo, emission, inward);
  if (caps)
  {
    const int rings = std::max(1, segments / 8);
    const float side = inward ? -1.f : 1.f;
    if (baseRadius > 0.f)
    {
      addDisk(base, basis.axis * -side, baseRadius, segments, rings, albedo, emission);
    }
    if (topRadius > 0.f)
    {
      addDisk(top, basis.axis * side, topRadius, segments, rings, albedo, emission);
    }
  }
  return first;
}

Index MeshBuilder::addTorus(const Vec3f& center, const Vec3f& axis, float majorRadius,
  float minorRadius, int majorSegments, int minorSegments, const Vec3f& albedo,
  const Vec3f& emission)
{
  const RingBasis basis(axis);
  return addGrid(
    [&](float u, float v)
    {
      const float theta = 2.f * kPi * v;
      return center + basis.ring(u) * (majorRadius + minorRadius * std::cos(theta)) +
        basis.axis * (minorRadius * std::sin(theta));
    },
    majorSegments, minorSegments, SurfaceTopology::torus(), albedo, emission, false);
}

Index MeshBuilder::addRevolution(const Vec3f& base, const Vec3f& axis,
  const std::vector<std::pair<float, float>>& profile, int segments, const Vec3f& albedo,
  const Vec3f& emission, bool inward)
{
  if (profile.size() < 2)
  {
    throw Error("MeshBuilder: a surface of revolution needs at least two profile points.");
  }
  const RingBasis basis(axis);
  const int n = int(profile.size()) - 1;
  const SurfaceTopology topology{ true, false, profile.front().first <= 0.f,
    profile.back().first <= 0.f };
  return addGrid(
    [&](float u, float v)
    {
      const auto& rh = profile[std::size_t(std::lround(v * float(n)))];
      return base + basis.axis * rh.second + basis.ring(u) * rh.first;
    },
    segments, n, topology, albedo, emission, inward);
}

Index MeshBuilder::addSurface(const std::function<Vec3f(float, float)>& point, int nu, int nv,
  SurfaceTopology topology, const Vec3f& albedo, const Vec3f& emission, bool inward)
{
  return addGrid(point, nu, nv, topology, albedo, emission, inward);
}

Index MeshBuilder::addGrid(const std::function<Vec3f(float, float)>& point, int nu, int nv,
  SurfaceTopology topology, const Vec3f& albedo, const Vec3f& emission, bool inward)
{
  atLeast(nu, topology.wrapU ? 3 : 1, "surface cells along u");
  atLeast(nv, topology.wrapV ? 3 : (topology.poleAtV0 && topology.poleAtV1 ? 2 : 1),
    "surface cells along v");
  if (topology.wrapV && (topology.poleAtV0 || topology.poleAtV1))
  {
    throw Error("MeshBuilder: a surface closed along v cannot have poles.");
  }
  const int columns = topology.wrapU ? nu : nu + 1;
  const int rows = topology.wrapV ? nv : nv + 1;
  const auto isPole = [&](int j)
  { return (j == 0 && topology.poleAtV0) || (j == nv && topology.poleAtV1); };

  const Index first = vertexCount();
  const std::size_t firstTriangle = target.triangles.size();
  std::vector<Index> rowStart(std::size_t(rows) + 1);
  for (int j = 0; j < rows; ++j)
  {
    rowStart[std::size_t(j)] = vertexCount();
    const float v = float(j) / float(nv);
    const int count = isPole(j) ? 1 : columns;
    for (int i = 0; i < count; ++i)
    {
      addVertex(point(float(i) / float(nu), v), Vec3f(0.f), albedo, emission);
    }
  }
  const auto at = [&](int i, int j)
  {
    j = topology.wrapV ? j % nv : j;
    if (isPole(j))
    {
      return rowStart[std::size_t(j)];
    }
    i = topology.wrapU ? i % nu : i;
    return rowStart[std::size_t(j)] + Index(i);
  };
  const auto emit = [&](Index a, Index b, Index c)
  {
    if (inward)
    {
      addTriangle(a, c, b);
    }
    else
    {
      addTriangle(a, b, c);
    }
  };
  for (int j = 0; j < nv; ++j)
  {
    for (int i = 0; i < nu; ++i)
    {
      // A pole row collapses the cell's quad into one triangle of the fan.
      if (!isPole(j))
      {
        emit(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      }
      if (!isPole(j + 1))
      {
        emit(at(i, j), at(i + 1, j + 1), at(i, j + 1));
      }
    }
  }
  smoothNormals(first, firstTriangle);
  return first;
}

void MeshBuilder::smoothNormals(Index firstVertex, std::size_t firstTriangle)
{
  for (Index v = firstVertex; v < vertexCount(); ++v)
  {
    target.normals[v] = Vec3f(0.f);
  }
  for (std::size_t t = firstTriangle; t < target.triangles.size(); ++t)
  {
    const Index* v = target.triangles[t].v;
    const Vec3f& a = target.positions[v[0]];
    // Unnormalized: the cross product's length weights each face by its area.
    const Vec3f n = cross(target.positions[v[1]] - a, target.positions[v[2]] - a);
    for (int k = 0; k < 3; ++k)
    {
      target.normals[v[k]] += n;
    }
  }
  for (Index v = firstVertex; v < vertexCount(); ++v)
  {
    target.normals[v] = normalize(target.normals[v]);
  }
}

void MeshBuilder::rotateY(Index firstVertex, const Vec3f& pivot, float radians)
{
  const float c = std::cos(radians), s = std::sin(radians);
  const auto rotate = [&](const Vec3f& d)
  { return Vec3f(c * d.x + s * d.z, d.y, -s * d.x + c * d.z); };
  for (Index v = firstVertex; v < vertexCount(); ++v)
  {
    target.positions[v] = pivot + rotate(target.positions[v] - pivot);
    target.normals[v] = rotate(target.normals[v]);
  }
}

void MeshBuilder::deform(Index firstVertex, const std::function<Vec3f(const Vec3f&)>& map)
{
  if (firstVertex >= vertexCount())
  {
    return;
  }
  // Difference step relative to the deformed part's size: small enough to resolve the map's
  // curvature, large enough that float rounding does not dominate the differences.
  Vec3f lo = target.positions[firstVertex], hi = lo;
  for (Index v = firstVertex; v < vertexCount(); ++v)
  {
    for (int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], target.positions[v][k]);
      hi[k] = std::max(hi[k], target.positions[v][k]);
    }
  }
  const float h = std::max(1e-3f * length(hi - lo), 1e-6f);
  const Vec3f ex(h, 0.f, 0.f), ey(0.f, h, 0.f), ez(0.f, 0.f, h);
  for (Index v = firstVertex; v < vertexCount(); ++v)
  {
    const Vec3f p = target.positions[v];
    const Vec3f a = (map(p + ex) - map(p - ex)) / (2.f * h);
    const Vec3f b = (map(p + ey) - map(p - ey)) / (2.f * h);
    const Vec3f c = (map(p + ez) - map(p - ez)) / (2.f * h);
    // Normals transform by the inverse transpose; the cofactor matrix is that times det > 0.
    const Vec3f& n = target.normals[v];
    target.normals[v] = normalize(cross(b, c) * n.x + cross(c, a) * n.y + cross(a, b) * n.z);
    target.positions[v] = map(p);
  }
}
}
