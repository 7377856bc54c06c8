// Instant radiosity's per-item math, for the CPU and the GPU alike (LINKGI_HOST_DEVICE):
// one VPL's irradiance at a vertex with the smoothstep-bounded geometry term of Marques &
// Santos 2010, imperfect visibility and interleaved subsets. The light paths that leave the
// VPLs are shared/LightPaths.h's.
#pragma once

#include "shared/Bounce.h"
#include "shared/DirectLight.h"
#include "shared/Gaps.h"
#include "shared/LightPaths.h"
#include "shared/Sampling.h"
#include "shared/Surface.h"

namespace linkgi::ir
{
using namespace linkgi::paths; // the light paths that leave the VPLs
/// Smoothstep of Marques & Santos: 0 below a = 0.8 dmin, 1 above b = 1.2 dmin.
LINKGI_HOST_DEVICE inline float distanceBound(float distance, float dmin)
{
  const float a = 0.8f * dmin, b = 1.2f * dmin;
  if (distance >= b)
  {
    return 1.f;
  }
  if (distance <= a)
  {
    return 0.f;
  }
  const float s = (distance - a) / (b - a);
  return s * s * (3.f - 2.f * s);
}

/// Irradiance VPL `vpl` gives at surface point `x` (unit side normal `n`) if visible, and the
/// shadow ray from `origin` (x off the surface) that decides whether it is: E = Phi/pi
/// cos_x cos_y / d^2 f(d) for a surface VPL, flux cos_x for a sky VPL. Zero (and no ray
/// needed) when either side faces away. The cosines take the surface points themselves, so
/// a vertex where two surfaces meet sees the other one as the link method's rays do.
LINKGI_HOST_DEVICE inline Vec3f vplIrradiance(const Vpl& vpl, const Vec3f& x, const Vec3f& origin,
  const Vec3f& n, float dmin, Ray& shadow)
{
  shadow.origin = origin;
  shadow.tnear = 0.f;
  if (vpl.sky)
  {
    const float c = dot(n, vpl.normal);
    shadow.direction = vpl.normal;
    shadow.tfar = 3.0e38f;
    return c > 0.f ? vpl.flux * c : Vec3f(0.f);
  }
  const Vec3f d = vpl.position - x;
  const float d2 = dot(d, d);
  shadow.direction = vpl.position + vpl.normal * vpl.offset - origin;
  shadow.tfar = 1.f - 1e-4f;
  if (!(d2 > 0.f))
  {
    return Vec3f(0.f);
  }
  const float invD = 1.f / std::sqrt(d2);
  const float cx = dot(n, d) * invD, cy = -dot(vpl.normal, d) * invD;
  if (cx <= 0.f || cy <= 0.f)
  {
    return Vec3f(0.f);
  }
  const float g = cx * cy / d2 * distanceBound(d2 * invD, dmin);
  return vpl.flux * (g * (1.f / kPi));
}

/// Imperfect visibility: a shadow ray against the proxy skips `margin` at both ends, where
/// the coarse surface passes near the fine one. False when nothing is left to test.
LINKGI_HOST_DEVICE inline bool proxyShadowRay(Ray& ray, float margin)
{
  const float length = std::sqrt(dot(ray.direction, ray.direction));
  ray.tnear = margin / length;
  if (ray.tfar < 1.f)
  {
    ray.tfar = 1.f - ray.tnear;
  }
  return ray.tnear < ray.tfar;
}

/// The VPL subset vertex v gathers under interleaved sampling (`subsets` > 1).
LINKGI_HOST_DEVICE inline std::uint32_t vertexSubset(Index v, std::uint32_t subsets, std::uint32_t seed)
{
  return subsets > 1 ? hash32(v ^ hash32(seed + 0x632be5abu)) % subsets : 0u;
}

/// Bias compensation (after Kollig & Keller 2004) as a gather over the update's own
/// per-vertex solution: what the clamp takes from element x is
///   E_c(x) = int (1 - f(d(w))) L(y(w)) cos dw  ~  pi / n sum_i (1 - f(d_i)) L(y_i)
/// over n = k*k cosine-weighted rays, one jittered within each cell of a k x k grid (twisted
/// per vertex; compensationRay), traced only as far as f's upper end, 1.2 dmin.
/// L(y) = Le + rho/pi (E_d + E_ind) interpolated from the hit triangle's elements, less the
/// corners in a gap the hit is not in (excludeGapCorners); but on a triangle with a corner
/// beyond 1.2 dmin of the hit, E_d is the lights' own at y, a shadow ray each (interpolated
/// from corners that far, it would lend a lit point beside the receiver the darkness of its
/// corners, or a shadowed one their light). The back of a one-sided triangle is black.
/// E_ind(y) is itself the clamped gather's, so what short paths add after their first
/// bounce stays out, and a compensated path may have one bounce more than `bounces`.
struct CompensationInputs
{
  const Triangle* triangles = nullptr;
  const Vec3f* positions = nullptr;
  const Vec3f* normals = nullptr;     ///< per vertex
  const RayOrigin* origins = nullptr; ///< rayOrigins: the offset of the shadow and gap rays
  const Vec3f* faceNormals = nullptr; ///< frontFaceNormals
  const Vec3f* albedo = nullptr;      ///< per vertex
  const Vec3f* emission = nullptr;    ///< per vertex, null: none
  const Vec3f* direct = nullptr;      ///< E_d per element
  const Light* lights = nullptr;
  Index lightCount = 0;
  Index vertexCount = 0;
  bool twoSided = false;
  float dmin = 0.f;
};

/// What jitters `element`'s compensation rays (compensationRay), for the seed.
LINKGI_HOST_DEVICE inline std::uint32_t compensationKey(std::uint32_t seed, Index element)
{
  return hash32(hash32(element) ^ (seed + 0x632be5abu));
}

/// Ray i of an element's k x k compensation rays from `origin` in `frame`; `key`: its
/// compensationKey.
LINKGI_HOST_DEVICE inline Ray compensationRay(const Vec3f& origin, const Frame& frame, std::uint32_t i,
  std::uint32_t k, float dmin, std::uint32_t key)
{
  // Jittered within its cell, not at the cell's centre: the surface nearer than 1.2 dmin
  // lies at grazing angles where the surface is concave (the inside of a lamp's shade, a
  // fold), and the centres of a k x k grid leave the band below an elevation of
  // acos(1 - 1/k) empty (29 degrees at 64 rays): there the compensation found nothing.
  const float u = (float(i % k) + hashToUnit(key, 2 * i)) / float(k);
  const float v = (float(i / k) + hashToUnit(key, 2 * i + 1)) / float(k);
  return Ray{ origin, 0.f, frame.toWorld(cosineHemisphere(u, v)), 1.2f * dmin };
}

/// (1 - f(d)) L(y) for one compensation ray and its hit (zero for a miss, a blocked back
/// side or a hit in a gap); `indirect(e)` reads E_ind of element e, `trace(ray)` the closest
/// Hit (for the gap test), `occluded(ray)` whether a shadow ray is blocked.
template <typename IndirectAt, typename Trace, typename Occluded>
LINKGI_HOST_DEVICE inline Vec3f compensationSample(const CompensationInputs& c, const Ray& ray, Hit h,
  const IndirectAt& indirect, const Trace& trace, const Occluded& occluded)
{
  if (h.triangle == kInvalidIndex)
  {
    return Vec3f(0.f);
  }
  const Vec3f faceNormal = c.faceNormals[h.triangle];
  const bool back = dot(ray.direction, faceNormal) > 0.f;
  if (back && !c.twoSided)
  {
    return Vec3f(0.f);
  }
  const Triangle t = c.triangles[h.triangle];
  const Vec3f y = ray.origin + ray.direction * h.t;
  const float hu = h.u, hv = h.v; // excludeGapCorners may reweight them
  excludeGapCorners(h, ray, c.triangles, c.positions, c.faceNormals, c.origins, c.twoSided, trace);
  if (isGapHit(h))
  {
    return Vec3f(0.f);
  }
  // E_d: the corners' where all lie within the compensation's reach of the hit; else the
  // lights' own at the hit (the corners of a triangle larger than that say nothing of the
  // light beside the receiver), on the side the ray sees, with the shading normal there (the
  // face's where the corners' normals cancel) and shadow rays from the triangle's offset.
  const float reach2 = 1.44f * c.dmin * c.dmin;
  bool exact = false;
  for (int j = 0; j < 3; ++j)
  {
    const Vec3f toCorner = c.positions[t.v[j]] - y;
    exact = exact || dot(toCorner, toCorner) > reach2;
  }
  Vec3f direct(0.f);
  if (exact)
  {
    Vec3f n = normalize(c.normals[t.v[0]] * (1.f - hu - hv) + c.normals[t.v[1]] * hu + c.normals[t.v[2]] * hv);
    n = (dot(n, n) > 0.f ? n : faceNormal) * (back ? -1.f : 1.f);
    direct = shadowedIrradiance(c.lights, c.lightCount, y, n, y + n * triangleOffset(c.origins, t), occluded);
  }
  const float bary[3] = { 1.f - h.u - h.v, h.u, h.v };
  Vec3f radiance(0.f);
  for (int j = 0; j < 3; ++j)
  {
    const Index v = t.v[j];
    const Index e = back ? v + c.vertexCount : v;
    const Vec3f le = (c.emission && !back) ? c.emission[v] : Vec3f(0.f);
    radiance += outgoingRadiance(c.albedo[v], exact ? direct : c.direct[e], indirect(e), le) * bary[j];
  }
  const float distance = h.t * std::sqrt(dot(ray.direction, ray.direction));
  return radiance * (1.f - distanceBound(distance, c.dmin));
}

/// What the gather of one element reads besides the VPLs.
struct GatherParams
{
  float dmin = 0.f;        ///< distanceBound's minimum distance
  float proxyMargin = 0.f; ///< > 0: shadow rays test the proxy (proxyShadowRay)
  std::uint32_t subsets = 1;
  std::uint32_t seed = 0;
};

}
