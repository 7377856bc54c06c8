// The ray-tracing backend interface: build, refit, closest hit and occlusion over batches.
#pragma once

#include "linkgi/Scene.h"

#include <memory>

namespace linkgi
{
struct Ray
{
  Vec3f origin;
  float tnear = 0.f;
  Vec3f direction; ///< need not be unit length; t is measured in its units
  float tfar = 3.0e38f;
};

struct Hit
{
  Index triangle = kInvalidIndex; ///< kInvalidIndex on a miss
  float u = 0.f, v = 0.f;         ///< hit = (1-u-v) * p[v0] + u * p[v1] + v * p[v2]
  float t = 0.f;
};

/// A ray tracer over one triangle mesh. trace() and occluded() are thread-safe and may be
/// called concurrently once build() or refit() has returned.
class RayTracer
{
public:
  virtual ~RayTracer() = default;
  virtual const char* name() const = 0;
  /// (Re)builds the acceleration structure. The arrays must stay alive and unchanged until
  /// the next build() or refit(): backends may reference them without copying.
  virtual void build(const std::vector<Vec3f>& positions, const std::vector<Triangle>& triangles) = 0;
  /// Updates the structure for moved positions; topology is that of the last build().
  virtual void refit(const std::vector<Vec3f>& positions) = 0;
  /// Closest hit for each ray.
  virtual void trace(const Ray* rays, Hit* hits, std::size_t count) const = 0;
  /// occluded[i] = 1 if anything lies on ray i between tnear and tfar, else 0.
  virtual void occluded(const Ray* rays, std::uint8_t* occluded, std::size_t count) const = 0;
};

/// `tracer`'s closest hit of one ray, as the host/device code that takes a `trace(ray)`
/// callable wants it (light paths, gap tests, gathers).
struct ClosestHit
{
  const RayTracer& tracer;
  Hit operator()(const Ray& ray) const
  {
    Hit h;
    tracer.trace(&ray, &h, 1);
    return h;
  }
};

/// Whether anything blocks one ray in `tracer`, as the host/device code that takes an
/// `occluded(ray)` callable wants it (shadow rays).
struct AnyHit
{
  const RayTracer& tracer;
  bool operator()(const Ray& ray) const
  {
    std::uint8_t blocked = 0;
    tracer.occluded(&ray, &blocked, 1);
    return blocked != 0;
  }
};

/// The CPU backend, on Embree 3. Embree errors are reported as linkgi::Error. Builds
/// without Embree throw linkgi::Error here.
std::unique_ptr<RayTracer> createEmbreeRayTracer();

/// Our own BVH (the GPU's layout and traversal) on the CPU, for builds without Embree.
std::unique_ptr<RayTracer> createBvhRayTracer();

/// The CPU ray tracer of this build: Embree where available, else createBvhRayTracer().
std::unique_ptr<RayTracer> createCpuRayTracer();
}
