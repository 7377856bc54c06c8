// linkgi-bench: one JSON object per line per scene and backend, with stage timings, ray
// rates, link counts, and a plain Embree rtcIntersect1 loop over the same rays measured in
// the same run, so the engine's overhead shows as a ratio.
#include "linkgi/Error.h"
#include "linkgi/Links.h"
#include "linkgi/Sampling.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <embree3/rtcore.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

namespace
{
using namespace linkgi;

struct Args
{
  std::vector<std::string> scenes = standardSceneNames();
  std::string backend = "cpu";
  SolverOptions options;
  int repeat = 3;
};

std::vector<std::string> split(const std::string& s)
{
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
  {
    out.push_back(item);
  }
  return out;
}

Args parse(int argc, char** argv)
{
  Args a;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        throw Error("Missing value after " + arg + ".");
      }
      return argv[++i];
    };
    if (arg == "--scenes")
      a.scenes = split(value());
    else if (arg == "--rays")
      a.options.raysPerVertex = std::stoul(value());
    else if (arg == "--bounces")
      a.options.bounces = std::stoul(value());
    else if (arg == "--repeat")
      a.repeat = std::max(1, std::stoi(value()));
    else if (arg == "--backend")
      a.backend = value();
    else
    {
      throw Error("Usage: linkgi-bench [--scenes a,b] [--rays 256] [--bounces 3] [--repeat 3] "
                  "[--backend cpu]; unknown argument " + arg + ".");
    }
  }
  if (a.backend != "cpu")
  {
    throw Error("Backend '" + a.backend + "' is not available in this build; use cpu.");
  }
  return a;
}

/// The link rays of the solver, materialised once.
std::vector<RTCRayHit> linkRays(const Scene& scene, const SolverOptions& o)
{
  const std::vector<Vec3f> dirs = makeDirectionSet(o.raysPerVertex);
  const std::vector<Vec3f> shifts = originShifts(scene, Topology::build(scene.vertexCount(), scene.triangles));
  const float eps = rayEpsilon(scene);
  std::vector<RTCRayHit> rays(scene.vertexCount() * dirs.size());
  tbb::parallel_for(std::size_t(0), scene.vertexCount(), [&](std::size_t v) {
    const Frame f = vertexFrame(scene.normals[v], o.twist, o.seed, Index(v));
    const Vec3f org = scene.positions[v] + scene.normals[v] * eps + shifts[v];
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
  });
  return rays;
}

/// Rays per second of a plain parallel rtcIntersect1 loop on a default Embree scene.
double bareEmbreeRaysPerSecond(const Scene& scene, std::vector<RTCRayHit> rays)
{
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
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 1024),
    [&](const tbb::blocked_range<std::size_t>& r) {
      RTCIntersectContext context;
      rtcInitIntersectContext(&context);
      for (std::size_t i = r.begin(); i < r.end(); ++i)
      {
        rtcIntersect1(rtc, &context, &rays[i]);
      }
    });
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rtcReleaseScene(rtc);
  rtcReleaseDevice(device);
  return rays.size() / s;
}

void benchScene(const std::string& name, const Args& args)
{
  const Scene scene = makeStandardScene(name);
  const std::vector<RTCRayHit> rays = linkRays(scene, args.options);
  SolverStats full;
  double msLight = 1e30, bare = 0;
  // The solver and the bare loop alternate, so both see the same machine load; each
  // figure is the best of `repeat` runs.
  for (int r = 0; r < args.repeat; ++r)
  {
    Solver solver;
    solver.update(scene, args.options);
    if (r == 0 || solver.stats().msLinks < full.msLinks)
    {
      full = solver.stats();
    }
    // A light-only change: move every light a little.
    Scene moved = scene;
    for (Light& l : moved.lights)
    {
      l.position += Vec3f(0.01f, 0.f, 0.01f) * boundingDiagonal(scene.positions);
    }
    solver.update(moved, args.options);
    if (solver.stats().builtLinks)
    {
      throw Error("A light-only change rebuilt the links.");
    }
    msLight = std::min(msLight, solver.stats().msTotal);
    bare = std::max(bare, bareEmbreeRaysPerSecond(scene, rays));
  }
  const double raysPerS = full.rays / (full.msLinks * 1e-3);
  std::printf("{\"scene\":\"%s\",\"backend\":\"%s\",\"threads\":%d,\"vertices\":%zu,\"triangles\":%zu,"
              "\"rays_per_vertex\":%u,\"bounces\":%u,\"rays\":%llu,\"rays_per_s\":%.4g,"
              "\"bare_embree_rays_per_s\":%.4g,\"ray_rate_ratio\":%.3f,"
              "\"links_raw\":%llu,\"links_compressed\":%llu,\"link_bytes\":%llu,\"light_rays\":%llu,"
              "\"ms_bvh\":%.3f,\"ms_links\":%.3f,\"ms_compress\":%.3f,\"ms_light_links\":%.3f,"
              "\"ms_bounces\":%.3f,\"ms_smoothing\":%.3f,\"ms_full_update\":%.3f,\"ms_light_update\":%.3f}\n",
    name.c_str(), args.backend.c_str(), workerCount(), scene.vertexCount(), scene.triangleCount(),
    args.options.raysPerVertex, args.options.bounces, (unsigned long long)full.rays, raysPerS, bare,
    raysPerS / bare, (unsigned long long)full.linksRaw, (unsigned long long)full.linksCompressed,
    (unsigned long long)full.linkBytes, (unsigned long long)full.lightRays, full.msBvh, full.msLinks,
    full.msCompress, full.msLightLinks, full.msBounces, full.msSmoothing, full.msTotal, msLight);
  std::fflush(stdout);
}
}

int main(int argc, char** argv)
{
  try
  {
    const Args args = parse(argc, argv);
    for (const std::string& name : args.scenes)
    {
      benchScene(name, args);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "linkgi-bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
