#include "shared/DirectLight.h"

#include "shared/Surface.h"

#include <atomic>

namespace linkgi
{
namespace
{
/// Visibility (1 = lit) of `count` sample points; origin(i, o) sets sample i's ray origin
/// and returns false for samples nobody needs, which are not traced and reported as 0.
std::vector<float> sampleVisibility(const Light& light, std::size_t count,
  const std::function<bool(std::size_t, Vec3f&)>& origin, const RayTracer& tracer,
  std::atomic<std::uint64_t>& rayCount, const char* stage, const ProgressCallback& progress)
{
  std::vector<float> visible(count, 0.f);
  parallelFor(stage, count, 512,
    [&](std::size_t begin, std::size_t end) {
      std::vector<Ray> rays;
      std::vector<Index> ids;
      std::vector<std::uint8_t> blocked;
      rays.reserve(end - begin);
      ids.reserve(end - begin);
      for (std::size_t i = begin; i < end; ++i)
      {
        Vec3f o;
        if (origin(i, o))
        {
          rays.push_back(shadowRay(light, o, directionToLight(light, o)));
          ids.push_back(Index(i));
        }
      }
      blocked.resize(rays.size());
      tracer.occluded(rays.data(), blocked.data(), rays.size());
      for (std::size_t k = 0; k < rays.size(); ++k)
      {
        visible[ids[k]] = blocked[k] ? 0.f : 1.f;
      }
      rayCount += rays.size();
    },
    progress);
  return visible;
}
}

DirectLightResult computeDirectLight(const Scene& scene, const Topology& topology,
  const std::vector<RayOrigin>& origins, const RayTracer& tracer, bool twoSided, bool oversampling,
  const ProgressCallback& progress)
{
  const Elements elements{ scene.vertexCount(), twoSided };
  const std::size_t nv = scene.vertexCount();
  DirectLightResult result;
  result.irradiance.assign(elements.count(), Vec3f(0.f));
  std::atomic<std::uint64_t> rays{ 0 };
  std::vector<Vec3f> unshadowed(nv);
  // Progress runs once over all shadow-ray passes (lights x sides x vertex/edge samples).
  const int sides = twoSided ? 2 : 1, samplesPerSide = oversampling ? 2 : 1;
  const double passes = double(scene.lights.size() * sides * samplesPerSide);
  int pass = 0;
  const auto passProgress = [&]() -> ProgressCallback {
    if (!progress)
    {
      return {};
    }
    const double lo = pass++ / passes;
    return [&progress, lo, passes](const char* stage, double f) { return progress(stage, lo + f / passes); };
  };

  for (const Light& light : scene.lights)
  {
    if (maxComponent(light.intensity) <= 0.f)
    {
      pass += sides * samplesPerSide;
      continue;
    }
    for (int side = 0; side < sides; ++side)
    {
      const float sign = side == 0 ? 1.f : -1.f;
      parallelRanges(nv, 1024, [&](std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
        {
          Vec3f toLight;
          unshadowed[v] =
            unshadowedIrradiance(light, scene.positions[v], scene.normals[v] * sign, toLight);
        }
      });
      const auto lit = [&unshadowed](Index v) { return maxComponent(unshadowed[v]) > 0.f; };
      const std::vector<float> vertexVisible = sampleVisibility(light, nv,
        [&](std::size_t v, Vec3f& o) {
          o = vertexLightOrigin(scene.positions[v], scene.normals[v], origins[v], sign);
          return lit(Index(v));
        },
        tracer, rays, "light links", passProgress());
      std::vector<float> edgeVisible;
      if (oversampling)
      {
        edgeVisible = sampleVisibility(light, topology.edges.size(),
          [&](std::size_t e, Vec3f& o) {
            const auto [a, b] = topology.edges[e];
            o = edgeLightOrigin(scene.positions[a], scene.positions[b], scene.normals[a],
              scene.normals[b], origins[a], origins[b], sign);
            return lit(a) || lit(b);
          },
          tracer, rays, "light links (one-ring)", passProgress());
      }
      parallelRanges(nv, 1024, [&](std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
        {
          if (!lit(Index(v)))
          {
            continue;
          }
          const float visible = oversampledVisibility(Index(v), vertexVisible.data(),
            edgeVisible.data(), topology.neighbourOffsets.data(), topology.vertexEdges.data(),
            oversampling);
          result.irradiance[v + side * nv] += unshadowed[v] * visible;
        }
      });
    }
  }
  result.shadowRays = rays;
  return result;
}

Vec3f lightIrradiance(const Light& light, const Vec3f& p, const Vec3f& n,
  const RayTracer& tracer, float eps, const Vec3f& shift)
{
  return shadowedIrradiance(&light, 1, p, n, p + n * eps + shift, AnyHit{ tracer });
}

Vec3f directIrradiance(const Scene& scene, const Vec3f& p, const Vec3f& n,
  const RayTracer& tracer, float eps, const Vec3f& shift)
{
  return shadowedIrradiance(scene.lights.data(), Index(scene.lights.size()), p, n, p + n * eps + shift,
    AnyHit{ tracer });
}
}
