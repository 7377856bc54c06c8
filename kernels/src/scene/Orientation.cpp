#include "linkgi/Orientation.h"

#include "shared/DirectLight.h"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <tuple>

namespace linkgi
{
namespace
{
/// Dense point index of every vertex: vertices split from one point share it.
std::vector<Index> densePoints(std::size_t vertices, const std::vector<std::uint64_t>& pointIds, std::size_t& points)
{
  std::vector<Index> dense(vertices);
  if (pointIds.empty())
  {
    std::iota(dense.begin(), dense.end(), Index(0));
    points = vertices;
    return dense;
  }
  std::vector<std::pair<std::uint64_t, Index>> byPoint(vertices);
  for (std::size_t v = 0; v < vertices; ++v)
  {
    byPoint[v] = { pointIds[v], Index(v) };
  }
  std::sort(byPoint.begin(), byPoint.end());
  points = 0;
  for (std::size_t i = 0; i < vertices; ++i)
  {
    if (i > 0 && byPoint[i].first != byPoint[i - 1].first)
    {
      ++points;
    }
    dense[byPoint[i].second] = Index(points);
  }
  points += vertices > 0 ? 1 : 0;
  return dense;
}

struct UnionFind
{
  std::vector<Index> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), Index(0)); }
  Index find(Index x)
  {
    while (parent[x] != x)
    {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void join(Index a, Index b) { parent[find(a)] = find(b); }
};

/// The edges (a, b), a < b, of the triangles over their points, bucketed by a (a counting
/// sort), each bucket sorted by b: the edges in (a, b) order. An edge of one triangle
/// borders a hole.
struct Edges
{
  std::vector<std::size_t> first; ///< bucket a: higher[first[a], first[a + 1])
  std::vector<Index> higher;

  Edges(const Scene& scene, const std::vector<Index>& point, std::size_t points) : first(points + 1, 0)
  {
    for (const Triangle& t : scene.triangles)
    {
      for (int k = 0; k < 3; ++k)
      {
        ++first[std::min(point[t.v[k]], point[t.v[(k + 1) % 3]]) + 1];
      }
    }
    std::partial_sum(first.begin(), first.end(), first.begin());
    higher.resize(first.back());
    std::vector<std::size_t> next(first.begin(), first.end() - 1);
    for (const Triangle& t : scene.triangles)
    {
      for (int k = 0; k < 3; ++k)
      {
        const Index a = point[t.v[k]], b = point[t.v[(k + 1) % 3]];
        higher[next[std::min(a, b)]++] = std::max(a, b);
      }
    }
    for (std::size_t a = 0; a < points; ++a)
    {
      std::sort(higher.begin() + std::ptrdiff_t(first[a]), higher.begin() + std::ptrdiff_t(first[a + 1]));
    }
  }

  /// Calls border(a, b) for every edge that one triangle alone has.
  template <typename Border>
  void forEachBorder(Border&& border) const
  {
    for (std::size_t a = 0; a + 1 < first.size(); ++a)
    {
      const auto begin = higher.begin() + std::ptrdiff_t(first[a]), end = higher.begin() + std::ptrdiff_t(first[a + 1]);
      for (auto i = begin; i != end;)
      {
        auto j = std::next(i);
        while (j != end && *j == *i)
        {
          ++j;
        }
        if (j - i == 1)
        {
          border(Index(a), *i);
        }
        i = j;
      }
    }
  }
};

/// Makes the points on the borders of `edges` that lie at one position one point
/// (renumbering `point` densely, `points` their new count); true where any were joined. A
/// surface whose points repeat along a seam (the surface of a structured grid that wraps
/// around, an OBJ file's vertices split by their texture coordinates, a triangle soup) has
/// borders there; joined, it is closed. Only border points are compared: a closed surface
/// costs nothing.
bool joinCoincidentPoints(const Scene& scene, const Edges& edges, std::vector<Index>& point, std::size_t& points)
{
  std::vector<Index> border;
  edges.forEachBorder([&border](Index a, Index b) {
    border.push_back(a);
    border.push_back(b);
  });
  if (border.empty())
  {
    return false;
  }
  std::vector<Index> vertexOf(points);
  for (std::size_t v = 0; v < point.size(); ++v)
  {
    vertexOf[point[v]] = Index(v);
  }
  const auto key = [&](Index p) {
    const Vec3f& x = scene.positions[vertexOf[p]];
    return std::make_tuple(x.x, x.y, x.z);
  };
  std::sort(border.begin(), border.end(), [&key](Index a, Index b) { return key(a) < key(b); });
  UnionFind same(points);
  bool joined = false;
  for (std::size_t i = 1; i < border.size(); ++i)
  {
    if (border[i] != border[i - 1] && key(border[i]) == key(border[i - 1]))
    {
      same.join(border[i], border[i - 1]);
      joined = true;
    }
  }
  if (!joined)
  {
    return false;
  }
  std::vector<Index> renumbered(points, kInvalidIndex);
  std::size_t count = 0;
  for (Index& p : point)
  {
    const Index root = same.find(p);
    if (renumbered[root] == kInvalidIndex)
    {
      renumbered[root] = Index(count++);
    }
    p = renumbered[root];
  }
  points = count;
  return true;
}

/// Per surface: its bounds, the length of its holes' borders, and integrals over its
/// front sides: area, vector area and enclosed volume.
struct SurfaceSums
{
  std::size_t triangles = 0;
  double lo[3] = { HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi[3] = { -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  double boundary = 0.0, area = 0.0, volume = 0.0;
  double vectorArea[3] = { 0.0, 0.0, 0.0 };
};

/// A triangle is a sliver where twice its area is under kSliver times its longest edge
/// squared (its height under a millionth of its length), and a speck where it is under
/// kSliver squared times its surface's size squared (about a millionth of that size across).
constexpr double kSliver = 1e-6;

void sub(const Vec3f& a, const double c[3], double out[3])
{
  out[0] = double(a.x) - c[0];
  out[1] = double(a.y) - c[1];
  out[2] = double(a.z) - c[2];
}
}

SurfaceOrientation findInwardSurfaces(const Scene& scene, const std::vector<std::uint64_t>& pointIds)
{
  SurfaceOrientation report;
  const std::size_t nv = scene.vertexCount(), nt = scene.triangleCount();
  if (nv == 0 || nt == 0 || (!pointIds.empty() && pointIds.size() != nv))
  {
    return report;
  }
  std::size_t points = 0;
  std::vector<Index> point = densePoints(nv, pointIds, points);
  Edges edges(scene, point, points);
  if (joinCoincidentPoints(scene, edges, point, points))
  {
    edges = Edges(scene, point, points);
  }
  std::vector<Index> vertexOf(points);
  for (std::size_t v = 0; v < nv; ++v)
  {
    vertexOf[point[v]] = Index(v);
  }

  // Surfaces: triangles joined through shared points.
  UnionFind surfaces(points);
  for (const Triangle& t : scene.triangles)
  {
    surfaces.join(point[t.v[0]], point[t.v[1]]);
    surfaces.join(point[t.v[1]], point[t.v[2]]);
  }
  std::vector<Index> rootOf(points);
  for (std::size_t p = 0; p < points; ++p)
  {
    rootOf[p] = surfaces.find(Index(p));
  }
  std::vector<Index> surfaceOfRoot(points, kInvalidIndex);
  std::vector<SurfaceSums> sums;
  const auto surfaceOf = [&](Index p) {
    const Index root = rootOf[p];
    if (surfaceOfRoot[root] == kInvalidIndex)
    {
      surfaceOfRoot[root] = Index(sums.size());
      sums.emplace_back();
    }
    return surfaceOfRoot[root];
  };
  edges.forEachBorder([&](Index a, Index b) {
    sums[surfaceOf(a)].boundary += length(scene.positions[vertexOf[a]] - scene.positions[vertexOf[b]]);
  });
  for (std::size_t v = 0; v < nv; ++v)
  {
    SurfaceSums& s = sums[surfaceOf(point[v])];
    const Vec3f& p = scene.positions[v];
    const double x[3] = { p.x, p.y, p.z };
    for (int k = 0; k < 3; ++k)
    {
      s.lo[k] = std::min(s.lo[k], x[k]);
      s.hi[k] = std::max(s.hi[k], x[k]);
    }
  }
  const double bentCosine = std::cos(kBentNormalDegrees * double(kPi) / 180.0);
  std::vector<double> nearest(nv, -1.0), vertexArea(nv, 0.0); // the cosine to the nearest triangle
  for (const Triangle& t : scene.triangles)
  {
    SurfaceSums& s = sums[surfaceOf(point[t.v[0]])];
    const double c[3] = { 0.5 * (s.lo[0] + s.hi[0]), 0.5 * (s.lo[1] + s.hi[1]), 0.5 * (s.lo[2] + s.hi[2]) };
    double a[3], b[3], d[3];
    sub(scene.positions[t.v[0]], c, a);
    sub(scene.positions[t.v[1]], c, b);
    sub(scene.positions[t.v[2]], c, d);
    const double e1[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    const double e2[3] = { d[0] - a[0], d[1] - a[1], d[2] - a[2] };
    const double w[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    const Vec3f n = scene.normals[t.v[0]] + scene.normals[t.v[1]] + scene.normals[t.v[2]];
    const double facing = w[0] * n.x + w[1] * n.y + w[2] * n.z;
    const double twiceArea = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    // A sliver's winding says nothing of a side, nor does a speck's: corners a rounding apart
    // (the seam of vtkParametricTorus: 2.5e-15 of its size) turn its cross product any way.
    const double e3[3] = { d[0] - b[0], d[1] - b[1], d[2] - b[2] };
    const double longest2 = std::max({ e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2],
      e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2], e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2] });
    const double size2 = (s.hi[0] - s.lo[0]) * (s.hi[0] - s.lo[0]) + (s.hi[1] - s.lo[1]) * (s.hi[1] - s.lo[1]) +
      (s.hi[2] - s.lo[2]) * (s.hi[2] - s.lo[2]);
    const bool sided = twiceArea > kSliver * std::max(longest2, kSliver * size2);
    report.againstWinding += sided && facing < 0.0 ? 1 : 0;
    const double front = facing < 0.0 ? -1.0 : 1.0;
    // The tetrahedron (centre, a, b, d), signed by the winding, turned to the normals' side.
    s.volume += front * (a[0] * w[0] + a[1] * w[1] + a[2] * w[2]) / 6.0;
    s.area += 0.5 * twiceArea;
    for (int k = 0; k < 3; ++k)
    {
      // In double: a normal scaled by a transform (1e-30 of unit length) squares to zero in float.
      const double nk[3] = { scene.normals[t.v[k]].x, scene.normals[t.v[k]].y, scene.normals[t.v[k]].z };
      const double scale = twiceArea * std::sqrt(nk[0] * nk[0] + nk[1] * nk[1] + nk[2] * nk[2]);
      if (sided && scale > 0.0)
      {
        const double cosine = front * (w[0] * nk[0] + w[1] * nk[1] + w[2] * nk[2]) / scale;
        nearest[t.v[k]] = std::max(nearest[t.v[k]], cosine);
      }
      vertexArea[t.v[k]] += twiceArea / 6.0;
    }
    for (int k = 0; k < 3; ++k)
    {
      s.vectorArea[k] += 0.5 * front * w[k];
    }
    ++s.triangles;
  }

  double totalArea = 0.0;
  for (std::size_t v = 0; v < nv; ++v)
  {
    const bool bent = vertexArea[v] > 0.0 && nearest[v] < bentCosine;
    totalArea += vertexArea[v];
    report.bentNormals += bent ? 1 : 0;
    report.bentNormalArea += bent ? vertexArea[v] : 0.0;
  }
  report.bentNormalArea = totalArea > 0.0 ? report.bentNormalArea / totalArea : 0.0;
  report.surfaces = sums.size();
  std::vector<Index> inwardOf(sums.size(), kInvalidIndex);
  for (std::size_t i = 0; i < sums.size(); ++i)
  {
    const SurfaceSums& s = sums[i];
    const double radius = 0.5 * std::sqrt((s.hi[0] - s.lo[0]) * (s.hi[0] - s.lo[0]) +
      (s.hi[1] - s.lo[1]) * (s.hi[1] - s.lo[1]) + (s.hi[2] - s.lo[2]) * (s.hi[2] - s.lo[2]));
    const double openArea = std::sqrt(s.vectorArea[0] * s.vectorArea[0] +
      s.vectorArea[1] * s.vectorArea[1] + s.vectorArea[2] * s.vectorArea[2]);
    // Small holes: a closed surface's vector area is zero, and moving the volume's
    // reference point within the bounds changes it by at most radius x |vector area|.
    const bool closed = s.boundary * s.boundary <= 3.0 * s.area;
    const double decisive = std::max(1e-3 * s.area * radius, 2.0 * radius * openArea);
    if (closed && s.volume < -decisive)
    {
      inwardOf[i] = Index(report.inward.size());
      report.inward.emplace_back();
      report.inward.back().lo = Vec3f(float(s.lo[0]), float(s.lo[1]), float(s.lo[2]));
      report.inward.back().hi = Vec3f(float(s.hi[0]), float(s.hi[1]), float(s.hi[2]));
    }
  }
  if (!report.inward.empty())
  {
    for (std::size_t v = 0; v < nv; ++v)
    {
      const Index k = inwardOf[surfaceOf(point[v])];
      if (k != kInvalidIndex)
      {
        report.inward[k].vertices.push_back(Index(v));
      }
    }
    for (std::size_t t = 0; t < nt; ++t)
    {
      const Index k = inwardOf[surfaceOf(point[scene.triangles[t].v[0]])];
      if (k != kInvalidIndex)
      {
        report.inward[k].triangles.push_back(Index(t));
      }
    }
  }
  return report;
}

namespace
{
/// The winding number of the front sides of `surface`'s triangles around p: the sum of
/// their signed solid angles (Van Oosterom and Strackee) over 4 pi; -1 inside an inward
/// closed surface, 0 outside.
double windingNumber(const Scene& scene, const InwardSurface& surface, const Vec3f& p)
{
  double sum = 0.0;
  for (const Index t : surface.triangles)
  {
    const Triangle& tri = scene.triangles[t];
    double r[3][3], len[3];
    for (int k = 0; k < 3; ++k)
    {
      const Vec3f& x = scene.positions[tri.v[k]];
      r[k][0] = double(x.x) - p.x;
      r[k][1] = double(x.y) - p.y;
      r[k][2] = double(x.z) - p.z;
      len[k] = std::sqrt(r[k][0] * r[k][0] + r[k][1] * r[k][1] + r[k][2] * r[k][2]);
    }
    const auto dot3 = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    const double c[3] = { r[1][1] * r[2][2] - r[1][2] * r[2][1], r[1][2] * r[2][0] - r[1][0] * r[2][2],
      r[1][0] * r[2][1] - r[1][1] * r[2][0] };
    const double det = dot3(r[0], c);
    const double den = len[0] * len[1] * len[2] + dot3(r[0], r[1]) * len[2] +
      dot3(r[0], r[2]) * len[1] + dot3(r[1], r[2]) * len[0];
    const double e1[3] = { r[1][0] - r[0][0], r[1][1] - r[0][1], r[1][2] - r[0][2] };
    const double e2[3] = { r[2][0] - r[0][0], r[2][1] - r[0][1], r[2][2] - r[0][2] };
    const double w[3] = { e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
      e1[0] * e2[1] - e1[1] * e2[0] };
    const Vec3f n = scene.normals[tri.v[0]] + scene.normals[tri.v[1]] + scene.normals[tri.v[2]];
    const double front = w[0] * n.x + w[1] * n.y + w[2] * n.z < 0.0 ? -1.0 : 1.0;
    sum += front * 2.0 * std::atan2(det, den);
  }
  return sum / (4.0 * 3.14159265358979323846);
}
}

bool hasLightInside(const Scene& scene, const InwardSurface& surface)
{
  const auto inside = [&](const Vec3f& p) {
    const bool inBounds = p.x >= surface.lo.x && p.y >= surface.lo.y && p.z >= surface.lo.z &&
      p.x <= surface.hi.x && p.y <= surface.hi.y && p.z <= surface.hi.z;
    return inBounds && std::abs(windingNumber(scene, surface, p)) >= 0.5;
  };
  for (const Light& light : scene.lights)
  {
    if (light.type != LightType::Directional && maxComponent(light.intensity) > 0.f && inside(light.position))
    {
      return true;
    }
  }
  if (scene.emission.empty())
  {
    return false;
  }
  // Emitters: the surface's own emission shines into its front; others count where they
  // are (at most 64 of them tested, evenly spread, so that a glowing mesh costs little).
  std::vector<unsigned char> own(scene.vertexCount(), 0);
  for (const Index v : surface.vertices)
  {
    own[v] = 1;
    if (maxComponent(scene.emission[v]) > 0.f)
    {
      return true;
    }
  }
  std::vector<Index> emitters;
  for (std::size_t v = 0; v < scene.vertexCount(); ++v)
  {
    if (!own[v] && maxComponent(scene.emission[v]) > 0.f)
    {
      emitters.push_back(Index(v));
    }
  }
  const std::size_t step = std::max<std::size_t>(1, emitters.size() / 64);
  for (std::size_t i = 0; i < emitters.size(); i += step)
  {
    if (inside(scene.positions[emitters[i]]))
    {
      return true;
    }
  }
  return false;
}

void flipNormals(Scene& scene, const InwardSurface& surface)
{
  for (const Index v : surface.vertices)
  {
    scene.normals[v] = -scene.normals[v];
  }
}

float litShareOfFronts(const Scene& scene, const std::vector<Vec3f>& direct)
{
  const std::size_t nv = std::min(scene.vertexCount(), direct.size());
  const std::size_t pairs = nv * std::max<std::size_t>(scene.lights.size(), 1);
  const std::size_t stride = std::max<std::size_t>(1, (pairs + kLitShareSamples - 1) / kLitShareSamples);
  double lit = 0.0, facing = 0.0;
  for (std::size_t v = 0; v < nv; v += stride)
  {
    for (const Light& light : scene.lights)
    {
      Vec3f toLight;
      facing += luminance(unshadowedIrradiance(light, scene.positions[v], scene.normals[v], toLight));
    }
    lit += luminance(direct[v]);
  }
  return facing > 0.0 ? float(std::min(1.0, lit / facing)) : 1.f;
}

bool litOnlyFromBehind(const Scene& scene)
{
  bool back = false;
  for (const Light& light : scene.lights)
  {
    if (!(maxComponent(light.intensity) > 0.f))
    {
      continue;
    }
    for (std::size_t v = 0; v < scene.vertexCount(); ++v)
    {
      Vec3f toLight;
      const Vec3f& p = scene.positions[v];
      const Vec3f& n = scene.normals[v];
      if (maxComponent(unshadowedIrradiance(light, p, n, toLight)) > 0.f)
      {
        return false; // a correctly facing scene leaves here at its first lit vertex
      }
      back = back || maxComponent(unshadowedIrradiance(light, p, -n, toLight)) > 0.f;
    }
  }
  return back;
}

std::vector<Index> surfaceLabels(const Scene& scene, std::size_t& count)
{
  const std::size_t nv = scene.vertexCount();
  UnionFind sets(nv);
  for (const Triangle& t : scene.triangles)
  {
    sets.join(t.v[0], t.v[1]);
    sets.join(t.v[1], t.v[2]);
  }
  std::vector<Index> label(nv, kInvalidIndex), out(nv);
  count = 0;
  for (std::size_t v = 0; v < nv; ++v)
  {
    Index& l = label[sets.find(Index(v))];
    if (l == kInvalidIndex)
    {
      l = Index(count++);
    }
    out[v] = l;
  }
  return out;
}
}
