// The yardstick of the CPU backend: a plain parallel rtcIntersect1 loop over the solver's
// link rays on a default Embree scene.
#include "methods/links/Links.h"
#include "cpu/Parallel.h"
#include "shared/Sampling.h"
#include "linkgi/Solver.h"

#include <embree3/rtcore.h>

#include <chrono>
#include <cstring>

namespace linkgi::bench
{
namespace
{
/// The link rays of the solver, materialised once.
std::vector<RTCRayHit> linkRays(const Scene& scene, const SolverOptions& o)
{
  const std::vector<Vec3f> dirs = makeDirectionSet(o.raysPerVertex);
  const std::vector<RayOrigin> origins = rayOrigins(scene, Topology::build(scene.vertexCount(), scene.triangles));
  std::vector<RTCRayHit> rays(scene.vertexCount() * dirs.size());
  parallelRanges(scene.vertexCount(), 64, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      const Frame f = vertexFrame(scene.normals[v], o.twist, o.seed, Index(v));
      const Vec3f org = elementRayOrigin(scene.positions[v], scene.normals[v], origins[v]);
      for (std::size_t k = 0; k < dirs.size(); ++k)
      {
        RTCRayHit& r = rays[v * dirs.size() + k];
        std::memset(&r, 0, sizeof(r));
        const Vec3f d = f.toWorld(dirs[k]);
        r.ray.org_x = org.x, r.ray.org_y = org.y, r.ray.org_z = org.z;
        r.ray.dir_x = d.x, r.ray.dir_y = d.y, r.ray.dir_z = d.z;
        r.ray.tfar = 3.0e38f;
        r.ray.mask = 0xffffffffu;
        r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      }
    }
  });
  return rays;
}
}

double bareEmbreeRaysPerSecond(const Scene& scene, const SolverOptions& options)
{
  std::vector<RTCRayHit> rays = linkRays(scene, options);
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene rtc = rtcNewScene(device);
  RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
    g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, scene.vertexCount()));
  auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
    g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, scene.triangleCount()));
  std::memcpy(vb, scene.positions.data(), 12 * scene.vertexCount());
  std::memcpy(ib, scene.triangles.data(), 12 * scene.triangleCount());
  rtcCommitGeometry(g);
  rtcAttachGeometry(rtc, g);
  rtcReleaseGeometry(g);
  rtcCommitScene(rtc);
  const auto start = std::chrono::steady_clock::now();
  parallelRanges(rays.size(), 1024, [&](std::size_t begin, std::size_t end) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t i = begin; i < end; ++i)
    {
      rtcIntersect1(rtc, &context, &rays[i]);
    }
  });
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rtcReleaseScene(rtc);
  rtcReleaseDevice(device);
  return rays.size() / s;
}
}
