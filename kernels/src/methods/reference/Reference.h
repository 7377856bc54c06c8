// Ground truth for the link solver: per-vertex Monte Carlo path tracing on the RayTracer
// interface. Slow on purpose (thousands of paths per vertex), simple enough to trust.
#pragma once

#include "cpu/Parallel.h"
#include "shared/RayTracer.h"
#include "linkgi/Scene.h"

#include <cstdint>
#include <vector>

namespace linkgi
{
struct ReferenceOptions
{
  /// M: cosine-weighted paths per vertex. The first floor(sqrt(M))^2 primary directions are
  /// jittered on a grid of the unit square (stratified), the rest uniform. Default 4096.
  std::uint32_t pathsPerVertex = 4096;
  /// B: bounces, i.e. surface hits per path, deterministic (no Russian roulette); a path may
  /// end with one more segment that escapes to the environment (see solveReference). Default 3.
  std::uint32_t bounces = 3;
  /// Results are a deterministic function of the seed, independent of the thread count.
  std::uint32_t seed = 1;
  /// Off (default): a ray that hits the back of a triangle is blocked and sees black.
  /// On: back sides reflect with the negated shading normal and the same albedo (they do
  /// not emit: emission is front-only), and every vertex gets a back element too.
  bool twoSided = false;
  /// Ray origins are moved this far along the normal to avoid self-hits.
  /// 0 (default): each vertex's offset as the solvers take it (linkgi::rayOrigins: 1% of
  /// its shortest edge, at most 1e-4 of the scene's diagonal).
  float rayOffset = 0.f;
};

/// Per-element results, laid out like linkgi::Solution: vertex i, and with twoSided the
/// back of vertex i at vertexCount + i.
struct ReferenceSolution
{
  std::vector<Vec3f> direct;   ///< exact irradiance from the scene's lights (visibility by shadow rays)
  std::vector<Vec3f> indirect; ///< Monte Carlo estimate of bounced light, emission and environment
};

/// Direct and indirect irradiance at every vertex (with options.twoSided also at every back
/// side). With B = options.bounces, the indirect part is
///   E_ind(x) = pi/M * sum_k R_B(ray_k),    ray_k the k-th cosine-weighted ray from x,
///   R_b(ray) = L_env(direction)                                        if the ray misses,
///            = 0                                                       if b = 0 or it hits a black back side,
///            = Le(y) + rho(y)/pi * (E_direct(y) + pi * R_{b-1}(ray'))  at its first hit y,
/// with one cosine-weighted continuation ray' from y, albedo, emission and shading normal
/// interpolated barycentrically at y, E_direct(y) exact (as lightIrradiance), and the back of a
/// triangle black unless twoSided (the front is the side its vertex normals agree with).
/// So the environment acts like a light at every surface: a path of B surface segments may
/// end with one more segment into the sky. This is the limit (n_C -> infinity) of what the
/// link solver computes: E_ind = E_env + W L after B Jacobi bounces of
/// L = Le + rho/pi (E_d + E_env + W L), started from W L = 0.
/// Throws linkgi::Error for inconsistent array sizes and linkgi::Aborted when `progress`
/// returns false.
ReferenceSolution solveReference(const Scene& scene, const ReferenceOptions& options = {},
  const ProgressCallback& progress = {});

/// The same on a tracer the caller has already built over scene.positions/triangles.
ReferenceSolution solveReference(const Scene& scene, const RayTracer& tracer,
  const ReferenceOptions& options = {}, const ProgressCallback& progress = {});
}
