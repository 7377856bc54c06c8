// linkgi-bench: one JSON object per line per scene and backend, with stage timings, ray
// rates, link counts and memory. On the CPU also a plain Embree rtcIntersect1 loop over the
// same rays (the engine's overhead as a ratio); on the GPU our bounce gather against
// cuSPARSE on the same matrix. --dump / --compare store and check solutions across backends.
#include "BenchProgressive.h"
#include "BenchScenes.h"
#include "BenchStats.h"
#include "BenchSolutions.h"

#include "cuda/Cuda.h"
#include "linkgi/Error.h"
#include "linkgi/Memory.h"
#include "shared/Metrics.h"
#include "cpu/Parallel.h"
#include "linkgi/Resolution.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#if LINKGI_HAVE_CUDA
#include "BenchCuda.h"
#endif

#include <malloc.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

namespace linkgi::bench
{
double bareEmbreeRaysPerSecond(const Scene& scene, const SolverOptions& options);
}

namespace
{
using namespace linkgi;
using bench::median;

struct Args
{
  std::vector<std::string> scenes = standardSceneNames();
  SolverOptions options;
  int repeat = 3;
  std::string dump, compare;
  bool bare = true, gather = true;
  std::size_t proxyVertices = 0; ///< also solve through a proxy of this many vertices
  bool proxyOnly = false; ///< only the proxy (a mesh too large for the full solve's budget)
  /// also solve with refinement up to this many vertices, default tolerance/rounds
  std::size_t refineVertices = 0;
  bool progressive = false; ///< only the progressive record (BenchProgressive.h)
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

Backend parseBackend(const std::string& name)
{
  if (name == "cpu")
    return Backend::Cpu;
  if (name == "cuda")
    return Backend::Cuda;
  if (name == "auto")
    return Backend::Auto;
  throw Error("Unknown backend '" + name + "'; use cpu, cuda or auto.");
}

Args parse(int argc, char** argv)
{
  Args a;
  a.options.backend = Backend::Cpu;
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
    else if (arg == "--method")
      a.options.method = methodByName(value());
    else if (arg == "--vpls")
      a.options.instantRadiosity.vplCount = std::stoul(value());
    else if (arg == "--interleave")
      a.options.instantRadiosity.interleave = std::stoul(value());
    else if (arg == "--compensation")
      a.options.instantRadiosity.compensationRays = std::stoul(value());
    else if (arg == "--proxy")
    {
      a.options.instantRadiosity.proxyResolution = std::stoul(value());
      a.options.instantRadiosity.proxyVisibility = a.options.instantRadiosity.proxyResolution > 0;
    }
    else if (arg == "--proxy-vertices")
      a.proxyVertices = std::stoull(value());
    else if (arg == "--proxy-only")
      a.proxyOnly = true;
    else if (arg == "--refine-vertices")
      a.refineVertices = std::stoull(value());
    else if (arg == "--memory-budget")
      a.options.memoryBudget = std::stoull(value());
    else if (arg == "--bins")
      a.options.implicitVisibility.binsPerSide = std::stoul(value());
    else if (arg == "--photons")
      a.options.photonMapping.photons = std::stoul(value());
    else if (arg == "--clusters")
      a.options.photonMapping.clusters = std::stoul(value());
    else if (arg == "--gather-rays")
      a.options.photonMapping.gatherRays = std::stoul(value());
    else if (arg == "--rays")
      a.options.raysPerVertex = std::stoul(value());
    else if (arg == "--bounces")
      a.options.bounces = std::stoul(value());
    else if (arg == "--repeat")
      a.repeat = std::max(1, std::stoi(value()));
    else if (arg == "--backend")
      a.options.backend = parseBackend(value());
    else if (arg == "--devices")
      a.options.cudaDevices = std::stoi(value());
    else if (arg == "--bvh-update")
    {
      const std::string mode = value();
      a.options.cudaBvhUpdate = mode == "refit" ? CudaBvhUpdate::Refit
        : mode == "rebuild"                     ? CudaBvhUpdate::Rebuild
                                                : CudaBvhUpdate::Auto;
    }
    else if (arg == "--bvh-build")
      a.options.cudaBvhBuild = value() == "sah" ? CudaBvhBuild::HostSah : CudaBvhBuild::Gpu;
    else if (arg == "--dump")
      a.dump = value();
    else if (arg == "--compare")
      a.compare = value();
    else if (arg == "--no-bare")
      a.bare = false;
    else if (arg == "--no-gather")
      a.gather = false;
    else if (arg == "--progressive")
      a.progressive = true;
    else
    {
      throw Error("Usage: linkgi-bench [--scenes a,b (isosurface:N = N vertices)] [--method " + methodNames("|") + "] "
                  "[--vpls 1024] [--interleave 1] [--compensation 64] [--proxy 0|N] [--bins 12] [--photons 262144] [--clusters 12288] [--gather-rays 144] [--proxy-vertices N [--proxy-only]] [--refine-vertices N] [--memory-budget BYTES] [--rays 256] [--bounces 3] [--repeat 3] "
                  "[--backend cpu|cuda|auto] [--devices N] [--bvh-update auto|rebuild|refit] [--bvh-build gpu|sah] "
                  "[--dump DIR] [--compare DIR] [--no-bare] [--no-gather] [--progressive]; unknown argument " +
        arg + ".");
    }
  }
  return a;
}

double peakHostMb()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;
}

/// Moves every light a little: a light-only change.
Scene movedLights(const Scene& scene)
{
  Scene moved = scene;
  for (Light& l : moved.lights)
  {
    l.position += Vec3f(0.01f, 0.f, 0.01f) * boundingDiagonal(scene.positions);
  }
  return moved;
}

/// The updates of one scene: the cold first one, `repeat` warm full ones (reset() forgets
/// every cached stage but keeps allocations), each followed by two light-only ones.
struct UpdateRuns
{
  SolverStats cold, full, light; ///< full and light: the fastest of their kind
  std::vector<double> fullTimes, linkTimes, lightTimes;
  std::string profile; ///< per run and GPU: [gpu, elements, batches, ms wall, trace, compress]
  Solution solution;
  /// Peak resident set of the solver's updates above what the process held before them
  /// (0 where /proc/self cannot say).
  std::uint64_t hostPeakBytes = 0;
  /// The same for the first (cold) update alone: what the memory budget's estimate is of.
  std::uint64_t hostPeakColdBytes = 0;
};

std::string linkProfile(const SolverStats& s)
{
  std::ostringstream out;
  for (std::size_t d = 0; d < s.msWallPerDevice.size(); ++d)
  {
    out << (d ? "," : "") << "[" << d << "," << s.linkedPerDevice[d] << "," << s.batchesPerDevice[d]
        << "," << s.msWallPerDevice[d] << "," << s.msTracePerDevice[d] << ","
        << s.msCompressPerDevice[d] << "]";
  }
  return out.str();
}

UpdateRuns runUpdates(const Scene& scene, const Args& args)
{
  const Scene moved = movedLights(scene);
  UpdateRuns runs;
  malloc_trim(0); // what an earlier scene freed would be reused without raising the peak
  const bool peakReset = resetPeakResident();
  const std::uint64_t residentBefore = residentBytes();
  Solver solver;
  solver.update(scene, args.options);
  runs.hostPeakColdBytes = peakReset ? peakResidentBytes() - residentBefore : 0;
  runs.cold = runs.full = solver.stats();
  double msLight = 1e30;
  for (int r = 0; r < args.repeat; ++r)
  {
    solver.reset();
    solver.update(scene, args.options);
    const SolverStats& st = solver.stats();
    runs.fullTimes.push_back(st.msTotal);
    runs.linkTimes.push_back(st.ms("Links") + st.ms("Compress"));
    const std::string profile = linkProfile(st);
    runs.profile += (runs.profile.empty() || profile.empty() ? "" : ",") + profile;
    if (st.msTotal < runs.full.msTotal || r == 0)
    {
      runs.full = st;
    }
    for (const Scene* s : { &moved, &scene })
    {
      solver.update(*s, args.options);
      if (solver.stats().ran("Links"))
      {
        throw Error("A light-only change rebuilt the links.");
      }
      runs.lightTimes.push_back(solver.stats().msTotal);
      if (solver.stats().msTotal < msLight)
      {
        msLight = solver.stats().msTotal;
        runs.light = solver.stats();
      }
    }
  }
  runs.solution = solver.solution();
  runs.hostPeakBytes = peakReset ? peakResidentBytes() - residentBefore : 0;
  return runs;
}

/// Medians next to the best runs, and where the time of the best light-only update and of
/// the full update went.
std::string timingJson(const UpdateRuns& runs)
{
  std::ostringstream out;
  out << ",\"median_ms\":{\"full_update\":" << median(runs.fullTimes) << ",\"link_generation\":"
      << median(runs.linkTimes) << ",\"light_update\":" << median(runs.lightTimes)
      << "},\"best_ms_link_generation\":"
      << *std::min_element(runs.linkTimes.begin(), runs.linkTimes.end())
      << ",\"ms_link_generation_runs\":[";
  for (std::size_t i = 0; i < runs.linkTimes.size(); ++i)
  {
    out << (i ? "," : "") << runs.linkTimes[i];
  }
  const SolverStats& l = runs.light;
  out << "],\"link_profile_runs\":[" << runs.profile << "],\"ms_prepare\":" << runs.full.msPrepare
      << ",\"ms_topology\":" << runs.full.ms("Topology") << ",\"light_update_ms\":{\"prepare\":"
      << l.msPrepare << ",\"upload\":" << l.ms("Geometry") << ",\"light_links\":" << l.ms("LightLinks")
      << ",\"bounces\":" << l.ms("Bounces") << ",\"finish\":" << l.ms("Smoothing") << "}";
  if (runs.full.devices > 0)
  {
    out << ",\"link_profile\":[" << linkProfile(runs.full) << "]";
  }
  return out.str();
}

/// Rays per second of a stage that traced `rays` in `ms`; 0 for a method that traces none
/// (implicit visibility), where rays / 0 ms would print nan, which is not JSON.
double raysPerSecond(std::uint64_t rays, double ms)
{
  return ms > 0.0 ? double(rays) / (ms * 1e-3) : 0.0;
}

std::string stagesJson(const SolverStats& s);

/// Deformations: same triangles, moved vertices (BVH refit or rebuild, links, all after):
/// the torso bends by 0.5, other scenes stretch by 3% vertically, and back, six steps after
/// a full update. The first step of a process also loads the kernels only a deformation runs
/// (ms_deform_first); ms_deform_update is the median of the next five, its stages the last's.
std::string deformationJson(const std::string& name, const Scene& scene, const Args& args)
{
  SceneParams bent;
  bent.deformation = 0.5f;
  Scene deformed = name == "torso" ? makeStandardScene("torso", bent) : scene;
  if (name != "torso")
  {
    for (Vec3f& p : deformed.positions)
    {
      p.y *= 1.03f;
    }
  }
  Solver deforming;
  deforming.update(scene, args.options);
  std::vector<double> steps;
  for (int step = 0; step < 6; ++step)
  {
    deforming.update(step % 2 ? scene : deformed, args.options);
    steps.push_back(deforming.stats().msTotal);
  }
  const SolverStats& d = deforming.stats();
  std::ostringstream out;
  out << ",\"ms_deform_update\":" << median(std::vector<double>(steps.begin() + 1, steps.end()))
      << ",\"ms_deform_first\":" << steps[0] << ",\"ms_deform_update_runs\":[";
  for (std::size_t i = 1; i < steps.size(); ++i)
  {
    out << (i > 1 ? "," : "") << steps[i];
  }
  out << "],\"deform_bvh\":\""
      << (d.builtBvh ? "rebuild" : "refit") << "\",\"deform_ms_bvh\":" << d.ms("Geometry") + d.ms("Topology")
      << ",\"deform_rays_per_s\":" << raysPerSecond(d.rays, std::max(d.ms("Links"), d.ms("Gather")))
      << ",\"deform_ms_prepare\":" << d.msPrepare << ",\"deform_stages_ms\":{" << stagesJson(d) << "}";
  return out.str();
}

/// The yardsticks measured in the same run: our bounce gather against cuSPARSE on the GPU,
/// a bare Embree loop on the CPU.
std::string yardstickJson(const Scene& scene, const SolverStats& full, const Args& args)
{
  std::ostringstream out;
#if LINKGI_HAVE_CUDA
  if (full.backend == "cuda" && args.gather)
  {
    const bench::GatherBenchmark g = bench::benchmarkGather(scene, args.options, 20);
    out << ",\"gather\":{\"rows\":" << g.rows << ",\"nnz\":" << g.nonZeros
        << ",\"useful_mb\":" << g.usefulBytes / 1e6 << ",\"ms_gather\":" << g.msGather
        << ",\"tb_per_s\":" << g.usefulBytes / (g.msGather * 1e-3) / 1e12
        << ",\"ms_fused_bounce\":" << g.msBounce << ",\"ms_cusparse_3spmv\":" << g.msCusparse
        << ",\"speedup_vs_cusparse\":" << g.msCusparse / g.msGather
        << ",\"max_rel_diff\":" << g.maxRelativeDifference << "}";
  }
#endif
#if LINKGI_HAVE_EMBREE
  if (full.backend == "cpu" && args.bare && full.ms("Links") > 0.0)
  {
    const double bare = bench::bareEmbreeRaysPerSecond(scene, args.options);
    out << ",\"bare_embree_rays_per_s\":" << bare << ",\"ray_rate_ratio\":"
        << full.rays / (full.ms("Links") * 1e-3) / bare;
  }
#endif
  (void)scene, (void)full, (void)args;
  return out.str();
}

/// The area-weighted mean over the vertices' front sides of the indirect irradiance (mean of
/// R, G, B): independent of the tessellation, so meshes of different sizes must agree.
std::string meanIndirectJson(const Scene& scene, const Solution& solution)
{
  const std::vector<float> areas = vertexAreas(scene);
  double sum = 0.0, area = 0.0;
  for (std::size_t v = 0; v < areas.size() && v < solution.indirect.size(); ++v)
  {
    const Vec3f& e = solution.indirect[v];
    sum += areas[v] * (double(e.x) + e.y + e.z) / 3.0;
    area += areas[v];
  }
  std::ostringstream out;
  out << ",\"mean_indirect_irradiance\":" << (area > 0.0 ? sum / area : 0.0);
  return out.str();
}

/// Every stage and part of the method that ran the update, by name: "Links":12.3,...
std::string stagesJson(const SolverStats& s)
{
  std::ostringstream out;
  for (std::size_t i = 0; i < s.stages.size(); ++i)
  {
    out << (i ? "," : "") << "\"" << s.stages[i].name << "\":" << s.stages[i].ms;
  }
  return out.str();
}

void printRecord(const std::string& name, const Scene& scene, const UpdateRuns& runs,
  const Args& args, const std::string& extra)
{
  const SolverStats& full = runs.full;
  std::ostringstream perDevice;
  for (std::size_t i = 0; i < full.linkedPerDevice.size(); ++i)
  {
    perDevice << (i ? "," : "") << full.linkedPerDevice[i];
  }
  // The stage that traced `rays`: the links, or instant radiosity's VPL gather.
  const double msLinks = std::max(full.ms("Links"), full.ms("Gather")), msCompress = full.ms("Compress");
  std::printf("{\"scene\":\"%s\",\"method\":\"%s\",\"backend\":\"%s\",\"device\":\"%s\",\"devices\":%d,"
              "\"threads\":%d,\"vertices\":%zu,\"triangles\":%zu,\"rays_per_vertex\":%u,\"bounces\":%u,"
              "\"rays\":%llu,\"rays_per_s\":%.4g,\"links_raw\":%llu,\"links_compressed\":%llu,"
              "\"link_bytes\":%llu,\"light_rays\":%llu,\"ms_bvh\":%.3f,\"ms_links\":%.3f,"
              "\"ms_compress\":%.3f,\"ms_link_generation\":%.3f,\"ms_light_links\":%.3f,"
              "\"ms_bounces\":%.3f,\"ms_smoothing\":%.3f,\"ms_full_update\":%.3f,"
              "\"ms_full_update_cold\":%.3f,\"ms_light_update\":%.3f,\"gpu_bytes_allocated\":%llu,"
              "\"host_peak_mb\":%.1f,\"vpls\":%llu,\"photons\":%llu,\"clusters\":%llu,\"linked_per_device\":[%s],\"stages_ms\":{%s}%s,\"note\":\"%s\"}\n",
    name.c_str(), full.method.c_str(), full.backend.c_str(), full.device.c_str(), full.devices,
    workerCount(), scene.vertexCount(), scene.triangleCount(), args.options.raysPerVertex,
    args.options.bounces, (unsigned long long)full.rays, raysPerSecond(full.rays, msLinks),
    (unsigned long long)full.counter("LinksRaw"), (unsigned long long)full.counter("LinksCompressed"),
    (unsigned long long)full.counter("LinkBytes"), (unsigned long long)full.lightRays,
    full.ms("Geometry") + full.ms("Topology"), msLinks, msCompress, msLinks + msCompress,
    full.ms("LightLinks"), full.ms("Bounces"), full.ms("Smoothing"), full.msTotal,
    runs.cold.msTotal, runs.light.msTotal, (unsigned long long)full.gpuBytesAllocated,
    peakHostMb(), (unsigned long long)full.counter("Vpls"), (unsigned long long)full.counter("Photons"),
    (unsigned long long)full.counter("Clusters"), perDevice.str().c_str(), stagesJson(full).c_str(), extra.c_str(),
    full.backendNote.c_str());
  for (const std::string& w : full.warnings)
  {
    std::fprintf(stderr, "linkgi-bench: %s: %s\n", name.c_str(), w.c_str());
  }
  std::fflush(stdout);
}

/// Peak memory per vertex (host: resident set; GPU: what the engine allocated) and the
/// budget's estimate of it.
std::string memoryJson(const Scene& scene, const UpdateRuns& runs)
{
  const double v = double(std::max<std::size_t>(1, scene.vertexCount()));
  const SolverStats& s = runs.cold;
  std::ostringstream out;
  // The warm updates re-link while the cached links are still held (they are given up at
  // the commit, so a failure keeps them): their peak is above the cold one.
  out << ",\"memory\":{\"host_peak_bytes\":" << runs.hostPeakBytes << ",\"host_peak_bytes_per_vertex\":"
      << double(runs.hostPeakBytes) / v << ",\"host_peak_cold_bytes_per_vertex\":" << double(runs.hostPeakColdBytes) / v << ",\"gpu_peak_bytes_per_vertex\":" << double(s.gpuBytesAllocated) / v
      << ",\"host_estimated_bytes\":" << s.hostBytesEstimated << ",\"device_estimated_bytes\":"
      << s.deviceBytesEstimated << ",\"budget_bytes\":" << s.memoryBudget << "}";
  return out.str();
}

/// The same scene through a ProxySolver: fresh solvers (decimation included) and light
/// moves, medians, and the carried indirect light against the full solve's: `full`'s when
/// it ran, else `reference`'s (one stored by --dump) when there is one.
std::string proxyJson(const Scene& scene, const UpdateRuns* full, const Solution* reference, const Args& args)
{
  const Scene moved = movedLights(scene);
  std::vector<double> fullTimes, lightTimes, decimate, transfer, inputDirect;
  Solution solution;
  std::size_t proxyVertices = 0;
  malloc_trim(0);
  const bool peakReset = resetPeakResident();
  const std::uint64_t residentBefore = residentBytes();
  for (int r = 0; r < args.repeat; ++r)
  {
    ProxySolver solver;
    auto t = std::chrono::steady_clock::now();
    solver.update(scene, args.options, args.proxyVertices);
    fullTimes.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count());
    decimate.push_back(solver.stats().ms("Decimate"));
    transfer.push_back(solver.stats().ms("Transfer"));
    solution = solver.solution();
    proxyVertices = solver.proxy().scene.vertexCount();
    t = std::chrono::steady_clock::now();
    solver.update(moved, args.options, args.proxyVertices);
    lightTimes.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count());
    inputDirect.push_back(solver.stats().ms("InputDirect"));
  }
  const std::uint64_t peak = peakReset ? peakResidentBytes() - residentBefore : 0;
  std::vector<float> areas = vertexAreas(scene);
  if (args.options.twoSided)
  {
    areas.insert(areas.end(), areas.begin(), areas.end());
  }
  std::ostringstream out;
  out << ",\"proxy\":{\"target_vertices\":" << args.proxyVertices << ",\"vertices\":" << proxyVertices
      << ",\"median_ms\":{\"full_update\":" << median(fullTimes) << ",\"decimate\":" << median(decimate)
      << ",\"transfer\":" << median(transfer) << ",\"light_update\":" << median(lightTimes)
      << ",\"input_direct\":" << median(inputDirect) << "},\"ms_full_update_runs\":[";
  for (std::size_t i = 0; i < fullTimes.size(); ++i)
  {
    out << (i ? "," : "") << fullTimes[i];
  }
  out << "]";
  if (full)
  {
    out << ",\"speedup_full_update\":" << median(full->fullTimes) / median(fullTimes);
    reference = &full->solution;
  }
  if (reference)
  {
    const ErrorMetrics e = relativeRmse(solution.indirect, reference->indirect, areas);
    out << ",\"indirect_rel_rmse_luminance\":" << e.relRmseLuminance << ",\"indirect_rel_rmse_max_channel\":"
        << std::max({ e.relRmse.x, e.relRmse.y, e.relRmse.z });
  }
  out << ",\"host_peak_bytes_per_vertex\":" << double(peak) / double(std::max<std::size_t>(1, scene.vertexCount()))
      << "}";
  return out.str();
}

/// The same scene through a RefiningSolver (default tolerance and rounds, the vertex budget
/// of --refine-vertices): fresh solvers, medians, and the peak per input vertex.
std::string refineJson(const Scene& scene, const Args& args)
{
  std::vector<double> times;
  std::size_t vertices = 0, rounds = 0;
  malloc_trim(0);
  const bool peakReset = resetPeakResident();
  const std::uint64_t residentBefore = residentBytes();
  RefinementOptions refinement;
  refinement.maxVertices = args.refineVertices;
  for (int r = 0; r < args.repeat; ++r)
  {
    RefiningSolver solver;
    const auto t = std::chrono::steady_clock::now();
    solver.update(scene, args.options, refinement);
    times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count());
    vertices = solver.refined().scene.vertexCount();
    rounds = solver.splitsPerRound().size();
  }
  const std::uint64_t peak = peakReset ? peakResidentBytes() - residentBefore : 0;
  std::ostringstream out;
  out << ",\"refined\":{\"max_vertices\":" << args.refineVertices << ",\"vertices\":" << vertices
      << ",\"rounds\":" << rounds << ",\"median_ms\":" << median(times)
      << ",\"host_peak_bytes_per_input_vertex\":" << double(peak) / double(std::max<std::size_t>(1, scene.vertexCount()))
      << ",\"host_peak_bytes_per_refined_vertex\":" << double(peak) / double(std::max<std::size_t>(1, vertices)) << "}";
  return out.str();
}

void benchScene(const std::string& name, const Args& args)
{
  const Scene scene = bench::makeScene(name);
  const std::string stored = args.compare.empty() ? std::string() : args.compare + "/" + name + ".bin";
  if (args.progressive)
  {
    std::printf("%s\n", bench::progressiveJson(name, scene, args.options, args.repeat).c_str());
    std::fflush(stdout);
    return;
  }
  if (args.proxyOnly)
  {
    Solution reference;
    const bool compared = !stored.empty() && std::ifstream(stored);
    if (compared)
    {
      reference = bench::readSolution(stored);
    }
    std::printf("{\"scene\":\"%s\",\"vertices\":%zu,\"triangles\":%zu,\"rays_per_vertex\":%u%s}\n", name.c_str(),
      scene.vertexCount(), scene.triangleCount(), args.options.raysPerVertex,
      proxyJson(scene, nullptr, compared ? &reference : nullptr, args).c_str());
    return;
  }
  const UpdateRuns runs = runUpdates(scene, args);
  std::string extra = timingJson(runs) + deformationJson(name, scene, args) +
    meanIndirectJson(scene, runs.solution) + memoryJson(scene, runs);
  if (!args.dump.empty())
  {
    bench::writeSolution(args.dump + "/" + name + ".bin", runs.solution);
  }
  if (!stored.empty() && std::ifstream(stored))
  {
    const Solution reference = bench::readSolution(stored);
    extra += ",\"agreement\":" + bench::agreement(scene, runs.solution, reference);
  }
  extra += yardstickJson(scene, runs.full, args);
  if (args.proxyVertices > 0)
  {
    extra += proxyJson(scene, &runs, nullptr, args);
  }
  if (args.refineVertices > 0)
  {
    extra += refineJson(scene, args);
  }
  printRecord(name, scene, runs, args, extra);
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
