// Reference solver: per-vertex Monte Carlo path tracing, the ground truth of the link solver.
// Paths are traced as small wavefronts (a chunk of paths of one vertex, one depth at a time)
// so that every RayTracer call gets a batch.
#include "methods/reference/Reference.h"

#include "shared/DirectLight.h"
#include "shared/Surface.h"
#include "shared/Sampling.h"

#include "linkgi/Error.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace linkgi
{
namespace
{
/// Paths of one vertex traced together; bounds the per-thread scratch memory.
constexpr std::uint32_t kChunk = 256;

std::uint64_t splitMix64(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

/// PCG32 (O'Neill 2014): small state, good statistics, cheap to seed per path.
class Pcg32
{
public:
  explicit Pcg32(std::uint64_t seed = 0)
  {
    next();
    state += seed;
    next();
  }
  std::uint32_t next()
  {
    const std::uint64_t old = state;
    state = old * 6364136223846793005ull + kIncrement;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }
  /// Uniform in [0, 1): 24 random bits, so the result never rounds up to 1.
  float uniform() { return static_cast<float>(next() >> 8) * (1.f / 16777216.f); }

private:
  static constexpr std::uint64_t kIncrement = 1442695040888963407ull;
  std::uint64_t state = 0;
};

/// One independent stream per (seed, element, path): the result does not depend on which
/// thread handles which vertex, nor on the order paths are processed in.
Pcg32 pathRng(std::uint32_t seed, std::size_t element, std::uint32_t path)
{
  const std::uint64_t key = splitMix64((std::uint64_t(seed) << 32) ^ std::uint64_t(element));
  return Pcg32(splitMix64(key + path));
}

/// Read-only data shared by all threads.
struct Context
{
  const Scene& scene;
  const RayTracer& tracer;
  const ReferenceOptions& options;
  std::vector<RayOrigin> origins; ///< per vertex, as the solvers' (rayOrigins)
  bool hasEmission = false;
  bool environmentBlack = true;
  std::vector<Vec3f> frontNormals; ///< per triangle, unit, on the vertex normals' side (frontFaceNormals)
};

/// What a path needs from the surface it hit.
struct SurfacePoint
{
  Vec3f position, normal, albedo, emission;
  float offset = 0.f; ///< of rays leaving it (triangleOffset)
};

/// Interpolated shading data at a hit; false if the hit is on a blocking (black) back side.
bool surfaceAt(const Context& ctx, const Ray& ray, const Hit& hit, SurfacePoint& s)
{
  const Scene& scene = ctx.scene;
  const Triangle& tri = scene.triangles[hit.triangle];
  const bool back = dot(ray.direction, ctx.frontNormals[hit.triangle]) > 0.f;
  if (back && !ctx.options.twoSided)
    return false;
  const float w = 1.f - hit.u - hit.v;
  const Index a = tri.v[0], b = tri.v[1], c = tri.v[2];
  s.position = scene.positions[a] * w + scene.positions[b] * hit.u + scene.positions[c] * hit.v;
  s.albedo = scene.albedo[a] * w + scene.albedo[b] * hit.u + scene.albedo[c] * hit.v;
  Vec3f n = normalize(scene.normals[a] * w + scene.normals[b] * hit.u + scene.normals[c] * hit.v);
  if (n == Vec3f(0.f)) // opposing vertex normals cancel: fall back to the face
    n = normalize(ctx.frontNormals[hit.triangle]);
  s.normal = back ? -n : n;
  s.offset = triangleOffset(ctx.origins.data(), tri);
  s.emission = Vec3f(0.f);
  if (ctx.hasEmission && !back)
    s.emission = scene.emission[a] * w + scene.emission[b] * hit.u + scene.emission[c] * hit.v;
  return true;
}

/// Scratch arrays of one chunk of paths, reused across the vertices of a thread.
struct Wavefront
{
  std::vector<Ray> rays;
  std::vector<Hit> hits;
  std::vector<Vec3f> throughput;
  std::vector<Pcg32> rngs;
  // Direct-light queries of the current depth: point, normal, weight rho/pi * throughput.
  std::vector<SurfacePoint> lit;
  std::vector<Vec3f> litWeight;
  std::vector<Ray> shadows;
  std::vector<Vec3f> shadowIrradiance;
  std::vector<std::uint8_t> blocked;
  std::vector<std::uint32_t> owner; ///< shadow ray k belongs to queued point owner[k]

  void resize(std::size_t n)
  {
    rays.resize(n);
    hits.resize(n);
    throughput.resize(n);
    rngs.resize(n);
    lit.resize(n);
    litWeight.resize(n);
    shadows.resize(n);
    shadowIrradiance.resize(n);
    blocked.resize(n);
    owner.resize(n);
  }
};

/// Adds the shadowed light irradiance at every queued point, weighted, to `sum`.
void gatherDirect(const Context& ctx, Wavefront& wf, std::size_t count, Vec3f& sum)
{
  for (const Light& light : ctx.scene.lights)
  {
    std::size_t m = 0;
    for (std::size_t i = 0; i < count; ++i)
    {
      const SurfacePoint& s = wf.lit[i];
      if (lightSample(light, s.position, s.normal, s.position + s.normal * s.offset,
            wf.shadowIrradiance[m], wf.shadows[m]))
        wf.owner[m++] = static_cast<std::uint32_t>(i);
    }
    if (m == 0)
      continue;
    ctx.tracer.occluded(wf.shadows.data(), wf.blocked.data(), m);
    for (std::size_t k = 0; k < m; ++k)
      if (!wf.blocked[k])
        sum += wf.litWeight[wf.owner[k]] * wf.shadowIrradiance[k];
  }
}

/// Segments a path may have: B that end on a surface, and, as in the link solver, where the
/// environment is part of every surface's fixed irradiance (like a light), one more that
/// counts only if it escapes to the environment.
std::uint32_t maxSegments(const Context& ctx)
{
  return ctx.options.bounces + (ctx.environmentBlack ? 0u : 1u);
}

/// Traces `count` primary rays already in `wf` through up to maxSegments(); returns the sum
/// of their radiance estimates L_1(y_k).
Vec3f traceChunk(const Context& ctx, Wavefront& wf, std::size_t count)
{
  const std::uint32_t bounces = ctx.options.bounces, segments = maxSegments(ctx);
  Vec3f sum(0.f);
  for (std::uint32_t depth = 1; depth <= segments && count > 0; ++depth)
  {
    ctx.tracer.trace(wf.rays.data(), wf.hits.data(), count);
    std::size_t alive = 0, lit = 0;
    for (std::size_t i = 0; i < count; ++i)
    {
      const Ray ray = wf.rays[i];
      const Vec3f throughput = wf.throughput[i];
      if (wf.hits[i].triangle == kInvalidIndex)
      {
        if (!ctx.environmentBlack)
          sum += throughput * ctx.scene.environment.radiance(normalize(ray.direction));
        continue;
      }
      SurfacePoint s;
      if (depth > bounces || !surfaceAt(ctx, ray, wf.hits[i], s))
        continue;
      sum += throughput * s.emission;
      if (s.albedo == Vec3f(0.f))
        continue;
      if (!ctx.scene.lights.empty())
      {
        wf.lit[lit] = s;
        wf.litWeight[lit++] = throughput * s.albedo * (1.f / kPi);
      }
      if (depth == segments)
        continue;
      // rho/pi * E(y) with E(y) ~ pi * L(z) from one cosine-weighted sample.
      Pcg32 rng = wf.rngs[i];
      const float u1 = rng.uniform(), u2 = rng.uniform();
      const Vec3f dir = Frame::fromNormal(s.normal).toWorld(cosineHemisphere(u1, u2));
      wf.rays[alive] = Ray{ s.position + s.normal * s.offset, 0.f, dir, 3.0e38f };
      wf.throughput[alive] = throughput * s.albedo;
      wf.rngs[alive++] = rng;
    }
    gatherDirect(ctx, wf, lit, sum);
    count = alive;
  }
  return sum;
}

/// E_ind at one element: pi/M times the sum of the radiance that M cosine-weighted paths bring.
Vec3f estimateIndirect(const Context& ctx, Wavefront& wf, const Vec3f& p, const Vec3f& n,
  float offset, std::size_t element)
{
  const std::uint32_t paths = ctx.options.pathsPerVertex;
  const auto strata = static_cast<std::uint32_t>(std::sqrt(static_cast<double>(paths)));
  const Frame frame = Frame::fromNormal(n);
  const Vec3f origin = p + n * offset;
  double total[3] = { 0.0, 0.0, 0.0 };
  for (std::uint32_t start = 0; start < paths; start += kChunk)
  {
    const std::uint32_t count = std::min(kChunk, paths - start);
    for (std::uint32_t i = 0; i < count; ++i)
    {
      const std::uint32_t path = start + i;
      Pcg32 rng = pathRng(ctx.options.seed, element, path);
      float u1 = rng.uniform(), u2 = rng.uniform();
      if (path < strata * strata) // jittered grid: one sample per cell
      {
        u1 = (static_cast<float>(path % strata) + u1) / static_cast<float>(strata);
        u2 = (static_cast<float>(path / strata) + u2) / static_cast<float>(strata);
      }
      wf.rays[i] = Ray{ origin, 0.f, frame.toWorld(cosineHemisphere(u1, u2)), 3.0e38f };
      wf.throughput[i] = Vec3f(1.f);
      wf.rngs[i] = rng;
    }
    const Vec3f chunk = traceChunk(ctx, wf, count);
    for (int c = 0; c < 3; ++c)
      total[c] += chunk[c];
  }
  const double scale = kPi / static_cast<double>(paths);
  return { static_cast<float>(total[0] * scale), static_cast<float>(total[1] * scale),
    static_cast<float>(total[2] * scale) };
}

void checkScene(const Scene& scene, const ReferenceOptions& options)
{
  const std::size_t n = scene.vertexCount();
  if (n == 0 || scene.triangles.empty())
    throw Error("The reference solver needs a scene with vertices and triangles.");
  if (scene.normals.size() != n || scene.albedo.size() != n ||
    (!scene.emission.empty() && scene.emission.size() != n))
    throw Error("The scene's normals, albedo and emission arrays must have one entry per vertex.");
  for (const Triangle& t : scene.triangles)
    for (Index v : t.v)
      if (v >= n)
        throw Error("Triangle vertex index " + std::to_string(v) + " is out of range (" +
          std::to_string(n) + " vertices).");
  if (options.pathsPerVertex == 0)
    throw Error("The reference solver needs at least one path per vertex.");
}

}

ReferenceSolution solveReference(const Scene& scene, const ReferenceOptions& options,
  const ProgressCallback& progress)
{
  checkScene(scene, options);
  auto tracer = createCpuRayTracer();
  tracer->build(scene.positions, scene.triangles);
  return solveReference(scene, *tracer, options, progress);
}

ReferenceSolution solveReference(const Scene& scene, const RayTracer& tracer,
  const ReferenceOptions& options, const ProgressCallback& progress)
{
  checkScene(scene, options);
  Context ctx{ scene, tracer, options, {}, false, true, {} };
  ctx.hasEmission = !scene.emission.empty();
  ctx.environmentBlack = scene.environment.isBlack();
  ctx.frontNormals = frontFaceNormals(scene);

  const std::size_t vertices = scene.vertexCount();
  const std::size_t elements = options.twoSided ? 2 * vertices : vertices;
  // The same ray origins as the solvers: a vertex in a concave corner lies in the other
  // surface's plane, and rays starting on that plane leak through it.
  ctx.origins = rayOrigins(scene, Topology::build(vertices, scene.triangles));
  if (options.rayOffset > 0.f)
  {
    for (RayOrigin& o : ctx.origins)
    {
      o.offset = options.rayOffset;
    }
  }
  const std::vector<RayOrigin>& origins = ctx.origins;
  ReferenceSolution result;
  result.direct.resize(elements);
  result.indirect.resize(elements);
  parallelFor("Reference path tracing", elements, 1,
    [&](std::size_t begin, std::size_t end) {
      Wavefront wf;
      wf.resize(std::min(kChunk, options.pathsPerVertex));
      for (std::size_t e = begin; e < end; ++e)
      {
        const std::size_t v = e % vertices;
        const Vec3f n = e < vertices ? normalize(scene.normals[v]) : -normalize(scene.normals[v]);
        const Vec3f& p = scene.positions[v];
        const RayOrigin& o = origins[v];
        result.direct[e] = directIrradiance(scene, p, n, tracer, o.offset, o.shift);
        result.indirect[e] =
          maxSegments(ctx) > 0 ? estimateIndirect(ctx, wf, p + o.shift, n, o.offset, e) : Vec3f(0.f);
      }
    },
    progress);
  return result;
}
}
