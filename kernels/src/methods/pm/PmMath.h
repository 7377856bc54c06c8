// Photon mapping's per-item math, for the CPU backend (PhotonMapping.cpp) and the CUDA
// backend (PmKernels.cu) alike: a radiance estimate at a photon, the caustic estimate at a
// vertex, one final-gather ray, one vertex's interpolation. Searches are PmTypes.h's;
// scenes are the light paths' PathScene (shared/LightPaths.h), whose paths are the photons.
#pragma once

#include "methods/pm/PmTypes.h"

#include "shared/Gaps.h"
#include "shared/LightPaths.h"

namespace linkgi::pm
{
/// Photons count towards an estimate within 37 degrees of its normal.
constexpr float kEstimateCos = 0.8f;
/// Interpolants per vertex: its own cluster's sample and up to five more (Clusters).
constexpr int kInterpolants = 6;
/// A sample serves a vertex only where the offset between them leans at most this much
/// (sin 6 degrees) out of their mean tangent plane: see sharesTangentPlane.
constexpr float kPlaneSin = 0.1f;

/// Whether a sample at s (normal ns) may light the point x (normal n): whether each lies
/// near the other's tangent plane, against their mean normal n + ns. Ward's test of irradiance
/// caching (Ward, Rubinstein & Clear 1988) rejects samples in front of x, which see a
/// hemisphere x may not see (the top of a table over what lies under it); a sample behind x
/// across a gap (the floor under that table) sees one just as foreign, so both sides are
/// rejected. The mean normal makes the offset square to it on a sphere; the tolerance absorbs
/// vertex normals that differ from the surface's.
LINKGI_HOST_DEVICE inline bool sharesTangentPlane(const Vec3f& x, const Vec3f& n, const Vec3f& s, const Vec3f& ns)
{
  const Vec3f d = s - x, m = n + ns;
  const float along = dot(d, m);
  return along * along <= kPlaneSin * kPlaneSin * dot(d, d) * dot(m, m);
}

/// The photon map's arrays, borrowed (host or device).
struct PhotonsView
{
  PointTreeView tree; ///< over the positions
  const Vec3f* normals = nullptr;
  const Vec3f* flux = nullptr;
};

/// The surface as the estimates measure the area their photons can cover by: small
/// triangles that tile it (surfacePieces, PhotonMapping.h), a tree over their centroids,
/// their corners (three per piece), unit normals, areas and radii (the farthest a corner
/// lies from the centroid), and the largest radius. Empty: every estimate divides by its
/// whole disc.
struct SurfaceView
{
  PointTreeView tree; ///< over the pieces' centroids
  const Vec3f* corners = nullptr;
  const Vec3f* normals = nullptr;
  const float* areas = nullptr;
  const float* radii = nullptr;
  float reach = 0.f;
  bool twoSided = false; ///< photons land on backs too, with the back's normal
};

/// The signed area that the disc of radius sqrt(R2) about the origin shares with the
/// triangle (origin, a, b) in a plane (a and b as 2D coordinates): positive where a to b
/// turns counter-clockwise. Summed over a polygon's edges, the area the disc shares with it.
LINKGI_HOST_DEVICE inline float discWedgeArea(float ax, float ay, float bx, float by, float R2)
{
  const float dx = bx - ax, dy = by - ay;
  const float dd = dx * dx + dy * dy, ad = ax * dx + ay * dy, aa = ax * ax + ay * ay;
  // |a + t d|^2 = R2 at t = (-ad -+ sqrt(ad^2 - dd (aa - R2))) / dd: the segment's pieces
  // inside the disc are triangles with the origin, those outside sectors of the disc.
  float cuts[4] = { 0.f, 0.f, 1.f, 1.f };
  const float disc = ad * ad - dd * (aa - R2);
  if (dd > 0.f && disc > 0.f)
  {
    const float root = std::sqrt(disc);
    cuts[1] = fminf(fmaxf((-ad - root) / dd, 0.f), 1.f);
    cuts[2] = fminf(fmaxf((-ad + root) / dd, 0.f), 1.f);
  }
  float area = 0.f;
  for (int i = 0; i < 3; ++i)
  {
    const float s = cuts[i], e = cuts[i + 1];
    const float sx = ax + s * dx, sy = ay + s * dy, ex = ax + e * dx, ey = ay + e * dy;
    const float cr = sx * ey - sy * ex;
    const float m = 0.5f * (s + e), mx = ax + m * dx, my = ay + m * dy;
    const bool inside = i == 1 && dd > 0.f && disc > 0.f && mx * mx + my * my <= R2;
    area += inside ? 0.5f * cr : 0.5f * R2 * atan2f(cr, sx * ex + sy * ey);
  }
  return area;
}

/// The area of the triangle (p0, p1, p2) within distance sqrt(r2) of q.
LINKGI_HOST_DEVICE inline float triangleAreaInBall(const Vec3f& q, float r2, const Vec3f& p0, const Vec3f& p1,
  const Vec3f& p2)
{
  const Vec3f e1 = p1 - p0, e2 = p2 - p0, c = cross(e1, e2);
  const float twice = length(c);
  if (!(twice > 0.f))
  {
    return 0.f;
  }
  const auto in = [&](const Vec3f& p) { return dot(p - q, p - q) <= r2; };
  if (in(p0) && in(p1) && in(p2))
  {
    return 0.5f * twice; // a ball is convex
  }
  const Vec3f m = c * (1.f / twice);
  const float h = dot(q - p0, m), R2 = r2 - h * h;
  if (!(R2 > 0.f))
  {
    return 0.f;
  }
  const Vec3f centre = q - m * h, u = normalize(e1), w = cross(m, u);
  const Vec3f p[3] = { p0 - centre, p1 - centre, p2 - centre };
  float area = 0.f;
  for (int i = 0; i < 3; ++i)
  {
    const Vec3f& a = p[i];
    const Vec3f& b = p[(i + 1) % 3];
    area += discWedgeArea(dot(a, u), dot(a, w), dot(b, u), dot(b, w), R2);
  }
  return fabsf(area);
}

/// The area of surface that the photons within distance sqrt(r2) of q facing within 37
/// degrees of n can cover: the surface's pieces that face n's way, cut by that ball. Where
/// the surface is wider than the disc and flat that is the disc pi r2; at a contact with
/// another surface (a box's foot on the floor, a wall's corner) a half or a quarter of it;
/// on a part narrower than it (a leg, a wire, a vent's slat) a band of it.
LINKGI_HOST_DEVICE inline float photonArea(const SurfaceView& m, const Vec3f& q, const Vec3f& n, float r2)
{
  const float disc = kPi * r2;
  if (m.tree.count == 0)
  {
    return disc;
  }
  // A piece whose centroid lies within r - radius of q lies in the ball whole, one beyond
  // r + radius wholly outside it.
  const float r = std::sqrt(r2), reach = r + m.reach;
  float area = 0.f;
  visitNear(m.tree, q, [reach]() { return reach * reach; }, [&](Index i, float d2) {
    const float radius = m.radii[i], outer = r + radius, inner = r - radius;
    if (d2 > outer * outer)
    {
      return;
    }
    const float c = dot(m.normals[i], n);
    if (c > kEstimateCos || (m.twoSided && -c > kEstimateCos))
    {
      area += inner > 0.f && d2 <= inner * inner
        ? m.areas[i]
        : triangleAreaInBall(q, r2, m.corners[3 * i], m.corners[3 * i + 1], m.corners[3 * i + 2]);
    }
  });
  return area > 0.f ? area : disc;
}

/// The outgoing radiance a diffuse surface reflects at photon i (Christensen's precomputed
/// estimate) from its k nearest photons, as Jensen estimates it: the flux of those within 37
/// degrees of its normal / the area they can cover (photonArea) / pi, r the k-th one's
/// distance, or sqrt(max2) where fewer are that near; zero from fewer than two. Jensen's
/// pi r^2 alone darkened thin parts (a scanned spider's legs, 52% of their indirect light)
/// and contacts (a CAD case's corners) by the share of the disc they do not fill. The
/// search takes every photon, not only those facing its way: a photon on a thin part in a
/// crowd of photons facing elsewhere would otherwise search all of them. `radius2` gets r^2, the disc the estimate
/// speaks for. `heap`: room for k.
LINKGI_HOST_DEVICE inline Vec3f siteRadiance(const PhotonsView& p, const SurfaceView& surface, Index i,
  std::uint32_t k, float max2, Neighbour* heap, float& radius2)
{
  const Vec3f normal = p.normals[i];
  const Vec3f q = p.tree.points[i];
  const std::uint32_t found = kNearest(p.tree, q, k, max2, [](Index) { return true; }, heap);
  Vec3f sum(0.f);
  std::uint32_t facing = 0;
  for (std::uint32_t j = 0; j < found; ++j)
  {
    if (dot(p.normals[heap[j].index], normal) > kEstimateCos)
    {
      sum += p.flux[heap[j].index];
      ++facing;
    }
  }
  const float r2 = found == k ? heap[0].d2 : max2;
  radius2 = r2;
  if (facing < 2 || !(r2 > 0.f))
  {
    return Vec3f(0.f); // a lone photon says nothing about density
  }
  return sum * (1.f / (kPi * photonArea(surface, q, normal, r2)));
}

/// Caustic irradiance at a vertex (position x, normal n, albedo rho, one-ring area `area`)
/// from the caustic photons: a cone filter of radius R, the k-th nearest photon on its side
/// within sqrt(max2) (sqrt(max2) with fewer), but at least the radius of a disc as large as
/// the one-ring (3 x area), where the filter integrates like the vertex's hat function: a
/// caustic sharper than the mesh keeps its power instead of the one vertex that holds it
/// claiming a tiny disc's density. The flux reflected over rho. `heap`: room for k.
LINKGI_HOST_DEVICE inline Vec3f causticEstimate(const PhotonsView& c, const Vec3f& x, const Vec3f& n,
  const Vec3f& rho, float area, std::uint32_t k, float max2, Neighbour* heap)
{
  const auto sameSide = [&](Index j) { return dot(c.normals[j], n) > kEstimateCos; };
  const std::uint32_t found = kNearest(c.tree, x, k, max2, sameSide, heap);
  if (found == 0)
  {
    return Vec3f(0.f);
  }
  float r2 = found == k ? heap[0].d2 : max2;
  r2 = fmaxf(r2, 3.f * area / kPi);
  if (!(r2 > 0.f))
  {
    return Vec3f(0.f);
  }
  const float radius = std::sqrt(r2);
  Vec3f sum(0.f);
  forEachWithin(c.tree, x, r2, [&](Index j, float d2) {
    if (sameSide(j))
    {
      sum += c.flux[j] * fmaxf(0.f, 1.f - std::sqrt(d2) / radius);
    }
  });
  Vec3f out(0.f);
  for (int ch = 0; ch < 3; ++ch)
  {
    out[ch] = rho[ch] > 0.f ? sum[ch] * 3.f / (kPi * r2 * rho[ch]) : 0.f;
  }
  return out;
}

/// What one final-gather ray brings back.
struct GatherHit
{
  Vec3f radiance{ 0.f }; ///< photon-map radiance at a diffuse hit, the sky's on a miss
  float distance = 0.f;  ///< to the diffuse hit (for the harmonic mean), 0 on a miss
  bool hit = false;
};

/// A final-gather ray whose first hit `h` is known: mirrors and glass send it on (reflected,
/// or refracted with the Fresnel odds, by a hash of the sample's cluster and the ray's
/// number), up to kMaxSpecularBounces turns; then it reads the photon map's radiance at its
/// diffuse hit (the back of a one-sided surface is black; a back of a two-sided one was lit
/// by photons stored with the back's normal), or the sky. `trace(ray)` returns the closest Hit.
template <typename Trace>
LINKGI_HOST_DEVICE inline GatherHit shadeGatherRay(const paths::PathScene& s, const RadianceSitesView& sites,
  Ray ray, Hit h, std::uint32_t cluster, std::uint32_t r, bool twoSided, const Trace& trace)
{
  for (std::uint32_t turn = 1; turn <= paths::kMaxSpecularBounces; ++turn)
  {
    const std::uint8_t material = h.triangle != kInvalidIndex && s.materials ? s.materials[h.triangle] : 0u;
    if (material == std::uint8_t(MaterialType::Diffuse))
    {
      break;
    }
    const Vec3f fn = s.faceNormals[h.triangle];
    const Triangle& t = s.triangles[h.triangle];
    const float b0 = 1.f - h.u - h.v;
    const Vec3f p = s.positions[t.v[0]] * b0 + s.positions[t.v[1]] * h.u + s.positions[t.v[2]] * h.v;
    const Vec3f n = paths::hitNormal(s, t, h.u, h.v, fn);
    const Vec3f d = normalize(ray.direction);
    const bool back = dot(d, fn) > 0.f;
    const Vec3f facing = back ? -n : n;
    const float ior = s.ior ? s.ior[h.triangle] : 1.5f;
    const Vec3f next = material == std::uint8_t(MaterialType::Mirror)
      ? paths::reflect(d, facing)
      : paths::dielectricDirection(d, facing, back ? ior : 1.f / ior, hashToUnit(hash32(cluster) ^ r, turn));
    ray.origin = p + (dot(next, fn) > 0.f ? fn : -fn) * triangleOffset(s.origins, t);
    ray.direction = next;
    ray.tnear = 0.f;
    ray.tfar = 3.0e38f;
    h = trace(ray);
  }
  GatherHit out;
  if (h.triangle == kInvalidIndex)
  {
    out.radiance = paths::skyRadiance(s, normalize(ray.direction));
    return out;
  }
  out.hit = true;
  out.distance = h.t * length(ray.direction);
  const Vec3f front = s.faceNormals[h.triangle];
  const bool back = dot(ray.direction, front) > 0.f;
  if (back && !twoSided)
  {
    return out;
  }
  const Vec3f fn = back ? -front : front;
  const Triangle& t = s.triangles[h.triangle];
  const float b0 = 1.f - h.u - h.v;
  const Vec3f y = s.positions[t.v[0]] * b0 + s.positions[t.v[1]] * h.u + s.positions[t.v[2]] * h.v;
  // The estimates' normals are their photons' (the shading normal of the side they landed
  // on): compared with the same at the hit.
  const Vec3f n = paths::hitNormal(s, t, h.u, h.v, front);
  const Index e = estimateAt(sites, y, back ? -n : n);
  if (e == kInvalidIndex)
  {
    return out;
  }
  // In a gap (under an object resting on the floor) the estimate's photons saw light the
  // hit does not.
  if (hitInGap(s.faceNormals, y, sites.tree.points[e], fn, out.distance, triangleOffset(s.origins, t), trace))
  {
    return out;
  }
  out.radiance = sites.radiance[e];
  return out;
}

/// Vertex v's irradiance from its interpolants' samples (row: kInterpolants clusters, its
/// own first, kInvalidIndex past the last), weighted as in irradiance caching:
/// w = 1 / (|x - s| / R + sqrt(2 - 2 n.n_s)) over samples facing the same way and not
/// off its tangent plane (sharesTangentPlane); its own cluster's when none qualifies, which
/// clusterVertices makes the vertex's own sample.
LINKGI_HOST_DEVICE inline Vec3f interpolateVertex(const Vec3f* positions, const Vec3f* normals, Index v,
  const Index* row, const Index* sample, const Vec3f* irradiance, const float* harmonicDistance)
{
  Vec3f sum(0.f);
  float weights = 0.f;
  for (int i = 0; i < kInterpolants && row[i] != kInvalidIndex; ++i)
  {
    const Index j = row[i], sv = sample[j];
    const float c = dot(normals[v], normals[sv]);
    if (c <= 0.f || !sharesTangentPlane(positions[v], normals[v], positions[sv], normals[sv]))
    {
      continue;
    }
    const float e = length(positions[v] - positions[sv]) / fmaxf(harmonicDistance[j], 1e-30f) +
      std::sqrt(fmaxf(0.f, 2.f - 2.f * c));
    const float w = 1.f / fmaxf(e, 1e-4f);
    sum += irradiance[j] * w;
    weights += w;
  }
  return weights > 0.f ? sum / weights : irradiance[row[0]];
}
}
