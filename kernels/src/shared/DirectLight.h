// Light links: shadow rays from each vertex (and its one-ring) to each light.
#pragma once

#include "cpu/Parallel.h"
#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"
#include "scene/Topology.h"

#include <vector>

namespace linkgi
{
/// Direction of the shadow ray from p: unnormalized for point and spot lights, so that
/// t = 1 reaches the light; unit length for directional lights.
LINKGI_HOST_DEVICE inline Vec3f directionToLight(const Light& light, const Vec3f& p)
{
  return light.type == LightType::Directional ? -normalize(light.direction) : light.position - p;
}

/// Bounds of a point or spot light's intensity / r^2 near its own position, where it grows
/// without bound and would overflow single precision for a light within about 1e-19 of a
/// vertex. r is taken as at least kMinLightDistance (2^-40; validated scenes are rescaled
/// to a diagonal of at least 2^-16, so this is below the float resolution of their
/// positions), and the irradiance of one light is at most kMaxLightIrradiance, the bound
/// validation puts on emission (the bounces carry it without overflow). A light exactly at
/// the vertex (r^2 of 0, also when it underflows) gives nothing.
constexpr float kMinLightDistance = 9.094947e-13f; // 2^-40
constexpr float kMaxLightIrradiance = 1e30f;

/// The denominator of a point or spot light's falloff at squared distance r2 (> 0):
/// c + l r + q r^2 of its attenuation, r taken as at least kMinLightDistance. With the
/// default (0, 0, 1) it is r^2 exactly.
LINKGI_HOST_DEVICE inline float distanceFalloff(const Light& light, float r2)
{
  const float clamped = fmaxf(r2, kMinLightDistance * kMinLightDistance);
  const Vec3f& a = light.attenuation;
  return a.x + a.y * std::sqrt(clamped) + a.z * clamped;
}

/// What a point or spot light gives at squared distance r2 against a lamp of the same
/// intensity (1/r^2): r^2 / (c + l r + q r^2), exactly 1 for the default (0, 0, 1). Light paths
/// shot from a light (instant radiosity, photon mapping) carry a lamp's flux and take this
/// factor where they first land, so that they bounce the light that the direct light shows.
LINKGI_HOST_DEVICE inline float falloffAgainstInverseSquare(const Light& light, float r2)
{
  const float clamped = fmaxf(r2, kMinLightDistance * kMinLightDistance);
  return clamped / distanceFalloff(light, r2);
}

/// A spot light's intensity along unit direction d against its axis: cos^spotExponent inside
/// its cone, 0 outside; 1 for a point light.
LINKGI_HOST_DEVICE inline float spotFactor(const Light& l, const Vec3f& d)
{
  if (l.type != LightType::Spot)
  {
    return 1.f;
  }
  const float cosAxis = dot(d, normalize(l.direction));
  if (cosAxis < std::cos(l.coneAngleDegrees * (kPi / 180.f)))
  {
    return 0.f;
  }
  return l.spotExponent > 0.f ? std::pow(fmaxf(cosAxis, 0.f), l.spotExponent) : 1.f;
}

/// Irradiance at p (unit normal n) from one light, without visibility; also returns the
/// shadow ray direction `toLight` = directionToLight(light, p). Bounded: see above.
LINKGI_HOST_DEVICE inline Vec3f unshadowedIrradiance(const Light& light, const Vec3f& p, const Vec3f& n, Vec3f& toLight)
{
  toLight = directionToLight(light, p);
  if (light.type == LightType::Directional)
  {
    return light.intensity * fmaxf(0.f, dot(n, toLight));
  }
  const float r2 = dot(toLight, toLight);
  if (!(r2 > 0.f))
  {
    return Vec3f(0.f);
  }
  const float invR = 1.f / std::sqrt(r2);
  const float cosSurface = dot(n, toLight) * invR;
  if (cosSurface <= 0.f)
  {
    return Vec3f(0.f);
  }
  const float spot = spotFactor(light, toLight * -invR);
  if (!(spot > 0.f))
  {
    return Vec3f(0.f);
  }
  const float falloff = spot * cosSurface / distanceFalloff(light, r2);
  const Vec3f e = light.intensity * falloff;
  return Vec3f(fminf(e.x, kMaxLightIrradiance), fminf(e.y, kMaxLightIrradiance),
    fminf(e.z, kMaxLightIrradiance));
}

/// The shadow ray from `origin` towards a light, stopping just short of a point light.
LINKGI_HOST_DEVICE inline Ray shadowRay(const Light& light, const Vec3f& origin, const Vec3f& toLight)
{
  Ray r;
  r.origin = origin;
  r.direction = toLight;
  r.tnear = 0.f;
  r.tfar = light.type == LightType::Directional ? 3.0e38f : 1.f - 1e-4f;
  return r;
}

/// Unshadowed irradiance of one light at (p, n) and the shadow ray from `origin` that
/// decides visibility. Returns false when the light cannot contribute.
LINKGI_HOST_DEVICE inline bool lightSample(const Light& light, const Vec3f& p, const Vec3f& n,
  const Vec3f& origin, Vec3f& irradiance, Ray& shadow)
{
  Vec3f toLight;
  irradiance = unshadowedIrradiance(light, p, n, toLight);
  if (!(maxComponent(irradiance) > 0.f))
  {
    return false;
  }
  shadow = shadowRay(light, origin, directionToLight(light, origin));
  return true;
}

/// Shadowed irradiance at surface point p (unit normal n of the lit side) from lights[0,
/// count), each decided by a shadow ray from `origin` (p a little off the surface);
/// `occluded(ray)` tests one ray.
template <typename Occluded>
LINKGI_HOST_DEVICE inline Vec3f shadowedIrradiance(const Light* lights, Index count, const Vec3f& p,
  const Vec3f& n, const Vec3f& origin, const Occluded& occluded)
{
  Vec3f sum(0.f);
  for (Index i = 0; i < count; ++i)
  {
    Vec3f e;
    Ray shadow;
    if (lightSample(lights[i], p, n, origin, e, shadow) && !occluded(shadow))
    {
      sum += e;
    }
  }
  return sum;
}

/// Hat-weighted visibility of vertex v: its own sample (weight 1) and the midpoints of its
/// incident edges (weight 1/2 each) when oversampling.
LINKGI_HOST_DEVICE inline float oversampledVisibility(Index v, const float* vertexVisible,
  const float* edgeVisible, const Index* offsets, const Index* vertexEdges, bool oversampling)
{
  float visible = vertexVisible[v], weight = 1.f;
  if (oversampling)
  {
    for (Index i = offsets[v]; i < offsets[v + 1]; ++i)
    {
      visible += 0.5f * edgeVisible[vertexEdges[i]];
      weight += 0.5f;
    }
  }
  return visible / weight;
}

struct DirectLightResult
{
  std::vector<Vec3f> irradiance; ///< per element (back sides after front sides if two-sided)
  std::uint64_t shadowRays = 0;
};

/// E_d per element: the unshadowed irradiance at the vertex times its visibility. With
/// `oversampling`, visibility is the hat-weighted mean over the vertex (weight 1) and the
/// midpoints of its incident edges (weight 1/2 each) - the 1:4 subdivision points of its
/// one-ring - so a shadow edge crossing the one-ring darkens the vertex partially instead of
/// snapping on or off. Edge samples are shared by both end points.
DirectLightResult computeDirectLight(const Scene& scene, const Topology& topology,
  const std::vector<RayOrigin>& origins, const RayTracer& tracer, bool twoSided, bool oversampling,
  const ProgressCallback& progress = {});

/// Exact irradiance that one light delivers at point p with unit normal n, shadowed:
///   point:       V * I * max(0, cos) / r^2
///   spot:        the same times cos(angle to axis)^spotExponent inside the cone of half
///                angle coneAngleDegrees, 0 outside
///   directional: V * intensity * max(0, dot(n, -direction))
/// V comes from one shadow ray whose origin is p + eps * n + shift (for a vertex, its
/// linkgi::rayOrigins offset and shift; zero shift elsewhere); for point and spot
/// lights the ray stops just short of the light (linkgi::shadowRay).
Vec3f lightIrradiance(const Light& light, const Vec3f& p, const Vec3f& n,
  const RayTracer& tracer, float eps, const Vec3f& shift = {});

/// Sum of lightIrradiance over all lights of the scene.
Vec3f directIrradiance(const Scene& scene, const Vec3f& p, const Vec3f& n,
  const RayTracer& tracer, float eps, const Vec3f& shift = {});
}
