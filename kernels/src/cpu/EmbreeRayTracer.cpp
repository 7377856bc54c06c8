// The CPU ray tracer on Embree 3: one triangle geometry in a dynamic scene, refit in place
// when only positions change.
#include "shared/RayTracer.h"

#include "linkgi/Error.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <string>

namespace linkgi
{
namespace
{
class EmbreeRayTracer final : public RayTracer
{
public:
  EmbreeRayTracer()
  {
    // One error callback routes every Embree error to the next check instead of testing
    // each call.
    device = rtcNewDevice(nullptr);
    if (!device)
    {
      throw Error("Embree could not create a device (" + std::to_string(rtcGetDeviceError(nullptr)) + ").");
    }
    rtcSetDeviceErrorFunction(device, &EmbreeRayTracer::onError, this);
  }

  ~EmbreeRayTracer() override
  {
    release();
    rtcReleaseDevice(device);
  }

  const char* name() const override { return "embree"; }

  void build(const std::vector<Vec3f>& positions, const std::vector<Triangle>& triangles) override
  {
    build(positions, triangles, false);
  }

  void build(const std::vector<Vec3f>& positions, const std::vector<Triangle>& triangles, bool refittable)
  {
    release();
    scene = rtcNewScene(device);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
    geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    if (refittable)
    {
      // REFIT keeps the topology of the tree and only updates bounds on later commits,
      // which is what a deforming mesh needs.
      rtcSetSceneFlags(scene, RTC_SCENE_FLAG_DYNAMIC);
      rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_REFIT);
    }
    this->refittable = refittable;
    // Embree-owned buffers: they carry the padding Embree's SIMD loads need past the end.
    vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, sizeof(float) * 3, positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, sizeof(unsigned) * 3, triangles.size()));
    checkError("allocating the geometry buffers");
    std::memcpy(vertices, positions.data(), sizeof(Vec3f) * positions.size());
    std::memcpy(indices, triangles.data(), sizeof(Triangle) * triangles.size());
    vertexCount = positions.size();
    triangleCount = triangles.size();
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcCommitScene(scene);
    checkError("building the BVH");
  }

  void refit(const std::vector<Vec3f>& positions) override
  {
    if (!scene || positions.size() != vertexCount)
    {
      throw Error("Refit needs a previous build with the same number of vertices.");
    }
    if (!refittable)
    {
      // A static mesh gets the faster static tree; the first deformation rebuilds it as a
      // refittable one, and later deformations only refit.
      const auto* indices = static_cast<const Triangle*>(
        rtcGetGeometryBufferData(geometry, RTC_BUFFER_TYPE_INDEX, 0));
      const std::vector<Triangle> triangles(indices, indices + triangleCount);
      build(positions, triangles, true);
      return;
    }
    std::memcpy(vertices, positions.data(), sizeof(Vec3f) * positions.size());
    rtcUpdateGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0);
    rtcCommitGeometry(geometry);
    rtcCommitScene(scene);
    checkError("refitting the BVH");
  }

  void trace(const Ray* rays, Hit* hits, std::size_t count) const override
  {
    // One ray at a time: a 4x4 block of the 256 directions still spans a wide cone, and
    // rtcIntersect16 packets measured slower than single rays on these link rays.
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t i = 0; i < count; ++i)
    {
      RTCRayHit rh;
      setRay(rays[i], rh.ray);
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &context, &rh);
      Hit& h = hits[i];
      if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
      {
        h = Hit{};
        continue;
      }
      h.triangle = rh.hit.primID;
      h.u = rh.hit.u;
      h.v = rh.hit.v;
      h.t = rh.ray.tfar;
    }
  }

  void occluded(const Ray* rays, std::uint8_t* result, std::size_t count) const override
  {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t i = 0; i < count; ++i)
    {
      RTCRay r;
      setRay(rays[i], r);
      rtcOccluded1(scene, &context, &r);
      // Embree marks an occluded ray by setting tfar to -inf.
      result[i] = r.tfar < 0.f ? 1 : 0;
    }
  }

private:
  static void setRay(const Ray& in, RTCRay& out)
  {
    out.org_x = in.origin.x;
    out.org_y = in.origin.y;
    out.org_z = in.origin.z;
    out.tnear = in.tnear;
    out.dir_x = in.direction.x;
    out.dir_y = in.direction.y;
    out.dir_z = in.direction.z;
    out.time = 0.f;
    out.tfar = in.tfar;
    out.mask = 0xffffffffu;
    out.id = 0;
    out.flags = 0;
  }

  static void onError(void* self, RTCError code, const char* message)
  {
    auto* tracer = static_cast<EmbreeRayTracer*>(self);
    std::lock_guard<std::mutex> lock(tracer->errorMutex);
    if (tracer->lastError.empty())
    {
      tracer->lastError = "Embree error " + std::to_string(code) + ": " + (message ? message : "");
    }
  }

  void checkError(const char* what)
  {
    std::lock_guard<std::mutex> lock(errorMutex);
    if (!lastError.empty())
    {
      const std::string message = lastError;
      lastError.clear();
      throw Error(std::string("Ray tracing failed while ") + what + ": " + message +
        (message.find("out of memory") != std::string::npos ? " (out of memory)" : ""));
    }
  }

  void release()
  {
    if (geometry)
    {
      rtcReleaseGeometry(geometry);
      geometry = nullptr;
    }
    if (scene)
    {
      rtcReleaseScene(scene);
      scene = nullptr;
    }
    vertices = nullptr;
    vertexCount = triangleCount = 0;
  }

  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  RTCGeometry geometry = nullptr;
  float* vertices = nullptr;
  std::size_t vertexCount = 0;
  std::size_t triangleCount = 0;
  bool refittable = false;
  std::mutex errorMutex;
  std::string lastError;
};
}

std::unique_ptr<RayTracer> createEmbreeRayTracer()
{
  return std::make_unique<EmbreeRayTracer>();
}
}
