// Whether a gather ray's hit lies in a gap that the sample it reads is not in: the floor under
// an object resting on it, read from the lit floor beside the object. Host and device code,
// for every method whose gather reads a sample away from its hit (photon mapping's radiance
// estimates, implicit visibility's leaves drawn from their surface).
#pragma once

#include "shared/RayTracer.h"

#include <cmath>

namespace linkgi
{
/// A surface covers a point where it lies within 25 degrees of parallel to it: a gap between
/// nearly parallel surfaces (an object resting on the floor), not the far side of a fold.
constexpr float kCoverCos = 0.9f;

/// Whether a surface covers point p within `reach` along the unit direction n (off the
/// surface by `offset`), nearly parallel to it (kCoverCos). `trace(ray)` returns the
/// closest Hit; `faceNormals` are the traced triangles'.
template <typename Trace>
LINKGI_HOST_DEVICE inline bool coveredWithin(const Vec3f* faceNormals, const Vec3f& p, const Vec3f& n, float offset,
  float reach, const Trace& trace)
{
  Ray ray;
  ray.origin = p + n * offset;
  ray.direction = n;
  ray.tnear = 0.f;
  ray.tfar = reach;
  const Hit h = trace(ray);
  return h.triangle != kInvalidIndex && fabsf(dot(faceNormals[h.triangle], n)) > kCoverCos;
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
}
