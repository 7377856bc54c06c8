// Whether a gather ray's hit lies in a gap that the sample it reads is not in: the floor under
// an object resting on it, read from the lit floor beside the object. Host and device code,
// for every method whose gather reads a sample away from its hit (photon mapping's radiance
// estimates, implicit visibility's leaves drawn from their surface, the corners of the
// triangle that instant radiosity's compensation interpolates).
#pragma once

#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"

#include <cmath>

namespace linkgi
{
/// A surface covers a point where it lies within 25 degrees of parallel to it: a gap between
/// nearly parallel surfaces (an object resting on the floor), not the far side of a fold.
constexpr float kCoverCos = 0.9f;

/// How far along the unit direction n from point p (off the surface by `offset`) a surface
/// nearly parallel to it (kCoverCos) covers it, within `reach`; +infinity where none does (the
/// nearest surface that way is farther or not parallel). `trace(ray)` returns the closest
/// Hit; `faceNormals` are the traced triangles'.
template <typename Trace>
LINKGI_HOST_DEVICE inline float coverDistance(const Vec3f* faceNormals, const Vec3f& p, const Vec3f& n, float offset,
  float reach, const Trace& trace)
{
  Ray ray;
  ray.origin = p + n * offset;
  ray.direction = n;
  ray.tnear = 0.f;
  ray.tfar = reach;
  const Hit h = trace(ray);
  return h.triangle != kInvalidIndex && fabsf(dot(faceNormals[h.triangle], n)) > kCoverCos ? h.t : INFINITY;
}

/// Whether a surface covers point p within `reach` along n (coverDistance).
template <typename Trace>
LINKGI_HOST_DEVICE inline bool coveredWithin(const Vec3f* faceNormals, const Vec3f& p, const Vec3f& n, float offset,
  float reach, const Trace& trace)
{
  return coverDistance(faceNormals, p, n, offset, reach, trace) <= reach;
}

/// Whether a ray that met the surface at y after `t` reads, from a sample at `site` of that
/// surface, light that y does not get: the ray is shorter than the way from y to the sample
/// (a receiver that close may cover y: it looks into a gap), a surface covers y within that
/// way and none covers the sample. `facing`: the surface's unit normal on the receiver's side.
template <typename Trace>
LINKGI_HOST_DEVICE inline bool hitInGap(const Vec3f* faceNormals, const Vec3f& y, const Vec3f& site,
  const Vec3f& facing, float t, float offset, const Trace& trace)
{
  const float reach = length(site - y);
  return t < reach && coveredWithin(faceNormals, y, facing, offset, reach, trace) &&
    !coveredWithin(faceNormals, site, facing, offset, reach, trace);
}

/// The barycentric u of a hit whose every corner lies outside the gap it is in
/// (excludeGapCorners): it reads nothing, as the back of a one-sided triangle.
constexpr float kGapHitU = -1.f;

LINKGI_HOST_DEVICE inline bool isGapHit(const Hit& h)
{
  return h.u == kGapHitU;
}

/// How much farther than the cover over a hit a corner must lie for excludeGapCorners to
/// leave it out: a gap at least twice as deep as it is wide, whose inside sees at most 5% of
/// the light at its mouth (a slot between parallel planes, lit at its mouth), not the floor
/// under a chair's seat read from a corner beside the chair.
constexpr float kGapDepth = 2.f;

/// A hit read as its triangle's corners interpolated (instant radiosity's compensation), with
/// hitInGap for each corner that lies more than kGapDepth times the cover's distance away:
/// the corners whose light the hit does not get are left out and the others reweighted (u, v
/// rewritten); with none left, the hit becomes a gap hit (isGapHit). The cover over the hit
/// is traced once, no farther than the ray came (a gap's other side is no farther from the
/// hit than a receiver looking into it, and most often is that receiver) nor than the
/// farthest corner over kGapDepth: a short ray. A miss, a blocked back (one-sided) and a hit
/// at least as far from the receiver as from its corners stay as they are. `ray`: the ray
/// that made the hit.
template <typename Trace>
LINKGI_HOST_DEVICE inline void excludeGapCorners(Hit& h, const Ray& ray, const Triangle* triangles,
  const Vec3f* positions, const Vec3f* faceNormals, const RayOrigin* origins, bool twoSided, const Trace& trace)
{
  if (h.triangle == kInvalidIndex)
  {
    return;
  }
  Vec3f facing = faceNormals[h.triangle];
  if (dot(ray.direction, facing) > 0.f)
  {
    if (!twoSided)
    {
      return;
    }
    facing = -facing;
  }
  const Triangle tri = triangles[h.triangle];
  float bary[3] = { 1.f - h.u - h.v, h.u, h.v };
  const Vec3f y = positions[tri.v[0]] * bary[0] + positions[tri.v[1]] * bary[1] + positions[tri.v[2]] * bary[2];
  const float t = h.t * length(ray.direction);
  float reach[3], farthest = 0.f;
  for (int k = 0; k < 3; ++k)
  {
    reach[k] = length(positions[tri.v[k]] - y);
    farthest = fmaxf(farthest, reach[k]);
  }
  if (!(t < farthest))
  {
    return;
  }
  const float offset = triangleOffset(origins, tri);
  const float cover = coverDistance(faceNormals, y, facing, offset, fminf(t, farthest / kGapDepth), trace);
  if (cover == INFINITY)
  {
    return; // nothing parallel covers the hit: no gap
  }
  bool excluded = false;
  float kept = 0.f;
  for (int k = 0; k < 3; ++k)
  {
    if (t < reach[k] && kGapDepth * cover < reach[k] && bary[k] > 0.f &&
      !coveredWithin(faceNormals, positions[tri.v[k]], facing, offset, reach[k], trace))
    {
      bary[k] = 0.f;
      excluded = true;
    }
    kept += bary[k];
  }
  if (!excluded)
  {
    return;
  }
  if (kept > 0.f)
  {
    h.u = bary[1] / kept;
    h.v = bary[2] / kept;
  }
  else
  {
    h.u = h.v = kGapHitU;
  }
}
}

