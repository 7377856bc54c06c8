// linkgi-validate: accuracy of the link solver against the path-traced reference, as JSON
// lines: area-weighted relative RMSE of total irradiance (E_d + E_ind) per channel and for
// luminance, per scene; and the furnace error against L = Le / (1 - rho).
// With --refine-from CELL (cornell): the box built with cells of CELL metres (two triangles
// per wall for CELL >= 0.6) is solved plainly and with refinement, and both are measured on
// the published box's fine grid against the reference there.
#include "linkgi/Error.h"
#include "shared/Metrics.h"
#include "linkgi/Resolution.h"
#include "resolution/Decimate.h"
#include "methods/pm/PhotonMapping.h"
#include "methods/reference/Reference.h"
#include "linkgi/Scenes.h"
#include "linkgi/Solver.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

namespace
{
using namespace linkgi;

struct Args
{
  std::vector<std::string> scenes = { "cornell", "colorlamp", "torso", "tearoom" };
  SolverOptions options;
  std::uint32_t referenceFactor = 16; ///< reference paths per vertex = factor * n_C
  /// Instant radiosity: each VPL count of --vpls a,b,c against the same reference.
  std::vector<std::uint32_t> vplCounts;
  /// Refinement runs: the coarse input's cell size (0: none), and the refinement options.
  float refineFrom = 0.f;
  RefinementOptions refinement;
  /// Scenes with mirrors or glass: light paths of the caustic reference.
  std::uint32_t causticPaths = 1u << 24;
};

Args parse(int argc, char** argv)
{
  Args a;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    if (i + 1 >= argc)
    {
      throw Error("Usage: linkgi-validate [--scenes a,b] [--method " + methodNames("|") + "] "
                  "[--rays 256] [--bounces 3] [--smoothing 0] [--oversampling 1] "
                  "[--reference-factor 16] [--vpls 1024] [--clamp 0.02] [--interleave 1] [--compensation 64] [--photons 262144] [--clusters 12288] [--gather-rays 144] [--caustic-paths 16777216] "
                  "[--proxy 0|N] [--bins 12] [--seed 0] [--refine-from CELL] [--refine-tolerance 0.1] "
                  "[--refine-vertices N] [--refine-rounds 3]; " + arg +
        " needs a value.");
    }
    const std::string value = argv[++i];
    if (arg == "--scenes")
    {
      a.scenes.clear();
      std::stringstream ss(value);
      for (std::string s; std::getline(ss, s, ',');)
      {
        a.scenes.push_back(s);
      }
    }
    else if (arg == "--method")
      a.options.method = methodByName(value);
    else if (arg == "--vpls")
    {
      std::stringstream ss(value);
      for (std::string n; std::getline(ss, n, ',');)
      {
        a.vplCounts.push_back(std::stoul(n));
      }
      a.options.instantRadiosity.vplCount = a.vplCounts.front();
    }
    else if (arg == "--clamp")
      a.options.instantRadiosity.clampDistance = std::stof(value);
    else if (arg == "--interleave")
      a.options.instantRadiosity.interleave = std::stoul(value);
    else if (arg == "--compensation")
      a.options.instantRadiosity.compensationRays = std::stoul(value);
    else if (arg == "--proxy")
    {
      // 0: exact visibility; N: the proxy of N cells along the longest axis
      a.options.instantRadiosity.proxyVisibility = std::stoul(value) > 0;
      if (a.options.instantRadiosity.proxyVisibility)
        a.options.instantRadiosity.proxyResolution = std::stoul(value);
    }
    else if (arg == "--bins")
      a.options.implicitVisibility.binsPerSide = std::stoul(value);
    else if (arg == "--photons")
      a.options.photonMapping.photons = std::stoul(value);
    else if (arg == "--caustic-paths")
      a.causticPaths = std::stoul(value);
    else if (arg == "--clusters")
      a.options.photonMapping.clusters = std::stoul(value);
    else if (arg == "--gather-rays")
      a.options.photonMapping.gatherRays = std::stoul(value);
    else if (arg == "--seed")
      a.options.seed = std::stoul(value);
    else if (arg == "--rays")
      a.options.raysPerVertex = std::stoul(value);
    else if (arg == "--bounces")
      a.options.bounces = std::stoul(value);
    else if (arg == "--smoothing")
      a.options.smoothing = value != "0";
    else if (arg == "--oversampling")
      a.options.lightOversampling = value != "0";
    else if (arg == "--refine-from")
      a.refineFrom = std::stof(value);
    else if (arg == "--refine-tolerance")
      a.refinement.tolerance = std::stof(value);
    else if (arg == "--refine-vertices")
      a.refinement.maxVertices = std::stoul(value);
    else if (arg == "--refine-rounds")
      a.refinement.rounds = std::stoul(value);
    else if (arg == "--reference-factor")
      a.referenceFactor = std::max(1ul, std::stoul(value));
    else
      throw Error("Unknown argument " + arg + ".");
  }
  return a;
}

std::vector<Vec3f> sum(const std::vector<Vec3f>& a, const std::vector<Vec3f>& b)
{
  std::vector<Vec3f> t(a.size());
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    t[i] = a[i] + b[i];
  }
  return t;
}

/// The options of each run: one, or one per VPL count of --vpls.
std::vector<SolverOptions> runs(const Args& args)
{
  std::vector<SolverOptions> list;
  for (std::uint32_t n : args.vplCounts)
  {
    list.push_back(args.options);
    list.back().instantRadiosity.vplCount = n;
  }
  if (list.empty())
  {
    list.push_back(args.options);
  }
  return list;
}

/// Instant radiosity's options as JSON fields (empty for the other methods).
std::string methodJson(const SolverOptions& o)
{
  if (o.method == Method::PhotonMapping)
  {
    const PhotonMappingOptions& pm = o.photonMapping;
    return ",\"photons_asked\":" + std::to_string(pm.photons) + ",\"clusters_asked\":" +
      std::to_string(pm.clusters) + ",\"gather_rays\":" + std::to_string(pm.gatherRays) +
      ",\"estimate_photons\":" + std::to_string(pm.estimatePhotons);
  }
  if (o.method != Method::InstantRadiosity)
  {
    return "";
  }
  const InstantRadiosityOptions& ir = o.instantRadiosity;
  return ",\"clamp\":" + std::to_string(ir.clampDistance) + ",\"interleave\":" +
    std::to_string(ir.interleave) + ",\"compensation\":" + std::to_string(ir.compensationRays) +
    ",\"proxy\":" + std::to_string(ir.proxyVisibility ? ir.proxyResolution : 0);
}

void validateScene(const std::string& name, const Args& args)
{
  const Scene scene = makeStandardScene(name);
  ReferenceOptions ro;
  ro.pathsPerVertex = args.referenceFactor * args.options.raysPerVertex;
  ro.bounces = args.options.bounces;
  const auto start = std::chrono::steady_clock::now();
  const ReferenceSolution ref = solveReference(scene, ro);
  const double msReference =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (const SolverOptions& options : runs(args))
  {
    Solver solver;
    const Solution& sol = solver.update(scene, options);
    const ErrorMetrics e = relativeRmse(
      sum(sol.direct, sol.indirect), sum(ref.direct, ref.indirect), vertexAreas(scene));
    const ErrorMetrics ei = relativeRmse(sol.indirect, ref.indirect, vertexAreas(scene));
    std::printf("{\"scene\":\"%s\",\"method\":\"%s\",\"vertices\":%zu,\"rays_per_vertex\":%u,"
                "\"vpls\":%llu,\"bounces\":%u,\"smoothing\":%d,\"oversampling\":%d,\"reference_paths_per_vertex\":%u,\"rel_rmse_r\":%.4f,\"rel_rmse_g\":%.4f,"
                "\"rel_rmse_b\":%.4f,\"rel_rmse_luminance\":%.4f,\"indirect_rel_rmse_luminance\":%.4f,"
                "\"ms_solver\":%.1f,\"ms_reference\":%.1f%s}\n",
      name.c_str(), solver.stats().method.c_str(), scene.vertexCount(), options.raysPerVertex,
      (unsigned long long)solver.stats().counter("Vpls"), options.bounces, int(options.smoothing), int(options.lightOversampling), ro.pathsPerVertex, e.relRmse.x, e.relRmse.y, e.relRmse.z, e.relRmseLuminance,
      ei.relRmseLuminance, solver.stats().msTotal, msReference, methodJson(options).c_str());
    std::fflush(stdout);
  }
}

/// Refinement: a coarse build of the scene, plain and refined, measured on the fine build's
/// vertices (barycentric transfer, as the proxy's) against the reference there.
void validateRefinement(const std::string& name, const Args& args)
{
  if (name != "cornell")
  {
    throw Error("--refine-from builds only the cornell scene coarsely; got " + name + ".");
  }
  const Scene fine = makeStandardScene(name);
  SceneParams coarseParams;
  coarseParams.cornellCell = args.refineFrom;
  const Scene coarse = makeStandardScene(name, coarseParams);
  ReferenceOptions ro;
  ro.pathsPerVertex = args.referenceFactor * args.options.raysPerVertex;
  ro.bounces = args.options.bounces;
  const ReferenceSolution ref = solveReference(fine, ro);
  const std::vector<float> areas = vertexAreas(fine);
  const auto measure = [&](const Scene& mesh, const Solution& sol)
  {
    Scene checked = mesh;
    linkgi::validateScene(checked);
    const ProxyTransfer onFine = buildTransfer(fine, checked);
    return relativeRmse(onFine.apply(sum(sol.direct, sol.indirect)), sum(ref.direct, ref.indirect), areas)
      .relRmseLuminance;
  };
  Solver plain;
  const float before = measure(coarse, plain.update(coarse, args.options));
  RefiningSolver refining;
  refining.update(coarse, args.options, args.refinement);
  const float after = measure(refining.refined().scene, refining.solution());
  // The fine build itself, solved the same way, for comparison.
  Solver full;
  const float fineError = measure(fine, full.update(fine, args.options));
  std::printf("{\"scene\":\"%s\",\"method\":\"%s\",\"coarse_cell_m\":%.3f,\"coarse_vertices\":%zu,"
              "\"refined_vertices\":%zu,\"fine_vertices\":%zu,\"rounds\":%zu,\"tolerance\":%.3f,"
              "\"rays_per_vertex\":%u,\"reference_paths_per_vertex\":%u,\"coarse_rel_rmse_luminance\":%.4f,"
              "\"refined_rel_rmse_luminance\":%.4f,\"fine_rel_rmse_luminance\":%.4f,\"ms_refined\":%.1f,"
              "\"ms_fine\":%.1f}\n",
    name.c_str(), refining.stats().method.c_str(), args.refineFrom, coarse.vertexCount(),
    refining.refined().scene.vertexCount(), fine.vertexCount(), refining.splitsPerRound().size(),
    args.refinement.tolerance, args.options.raysPerVertex, ro.pathsPerVertex, before, after,
    fineError, refining.stats().msTotal, full.stats().msTotal);
  std::fflush(stdout);
}

/// Caustics (a scene with mirrors or glass, photon mapping): Solution::caustics against light
/// tracing splatted into the vertices (solveCausticReference): where the brightest vertex
/// is, in units of the reference peak's longest adjacent edge, and the caustic power.
void validateCaustics(const std::string& name, const Args& args)
{
  const Scene scene = makeStandardScene(name);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Vec3f> ref = solveCausticReference(scene, args.causticPaths, 1);
  const double msReference =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  Scene checked = scene; // the solver's vertices
  linkgi::validateScene(checked);
  const std::vector<float> area = vertexAreas(checked);
  const auto luminance = [](const Vec3f& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; };
  const auto peakAndPower = [&](const std::vector<Vec3f>& e, std::size_t& peak) {
    double power = 0.0, best = -1.0;
    for (std::size_t v = 0; v < e.size() && v < checked.vertexCount(); ++v)
    {
      power += luminance(e[v]) * area[v];
      if (luminance(e[v]) > best)
      {
        best = luminance(e[v]);
        peak = v;
      }
    }
    return power;
  };
  std::size_t refPeak = 0;
  const double refPower = peakAndPower(ref, refPeak);
  double spacing = 0.0;
  for (const Triangle& t : checked.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (t.v[k] == refPeak)
      {
        spacing = std::max({ spacing, double(length(checked.positions[t.v[(k + 1) % 3]] - checked.positions[refPeak])),
          double(length(checked.positions[t.v[(k + 2) % 3]] - checked.positions[refPeak])) });
      }
    }
  }
  for (const SolverOptions& options : runs(args))
  {
    Solver solver;
    const Solution& sol = solver.update(scene, options);
    std::size_t peak = 0;
    const double power = sol.caustics.empty() ? 0.0 : peakAndPower(sol.caustics, peak);
    const double offset = sol.caustics.empty() ? -1.0 : double(length(checked.positions[peak] - checked.positions[refPeak])) / std::max(spacing, 1e-30);
    std::printf("{\"scene\":\"%s\",\"method\":\"%s\",\"vertices\":%zu,\"caustic_photons_paths\":%u,"
                "\"photons\":%llu,\"caustic_peak_offset_spacings\":%.3f,\"caustic_power_ratio\":%.4f,"
                "\"reference_caustic_power\":%.5g,\"ms_solver\":%.1f,\"ms_reference\":%.1f%s}\n",
      name.c_str(), solver.stats().method.c_str(), checked.vertexCount(), args.causticPaths,
      (unsigned long long)solver.stats().counter("Photons"), offset, refPower > 0.0 ? power / refPower : 0.0, refPower,
      solver.stats().msTotal, msReference, methodJson(options).c_str());
    std::fflush(stdout);
  }
}

void validateFurnace(const Args& args)
{
  const Scene scene = makeStandardScene("furnace");
  for (SolverOptions o : runs(args))
  {
    o.bounces = 12; // residual rho^13 = 1e-4
    Solver solver;
    const Solution& sol = solver.update(scene, o);
    const std::vector<float> area = vertexAreas(scene);
    double worst = 0, mean = 0, total = 0;
    for (std::size_t v = 0; v < scene.vertexCount(); ++v)
    {
      const double ratio = sol.radiance[v].x * (1.0 - scene.albedo[v].x) / scene.emission[v].x;
      worst = std::max(worst, std::abs(ratio - 1.0));
      mean += area[v] * ratio;
      total += area[v];
    }
    std::printf("{\"scene\":\"furnace\",\"method\":\"%s\",\"vertices\":%zu,\"rays_per_vertex\":%u,"
                "\"vpls\":%llu,\"bounces\":%u,\"max_rel_error\":%.5f,\"mean_rel_error\":%.5f,"
                "\"ms_solver\":%.1f}\n",
      solver.stats().method.c_str(), scene.vertexCount(), o.raysPerVertex,
      (unsigned long long)solver.stats().counter("Vpls"), o.bounces, worst, std::abs(mean / total - 1.0),
      solver.stats().msTotal);
  }
}
}

int main(int argc, char** argv)
{
  try
  {
    const Args args = parse(argc, argv);
    if (args.refineFrom > 0.f)
    {
      for (const std::string& name : args.scenes)
      {
        validateRefinement(name, args);
      }
      return 0;
    }
    validateFurnace(args);
    for (const std::string& name : args.scenes)
    {
      if (name == "caustics" || name == "cornell-glass")
      {
        validateCaustics(name, args);
        continue;
      }
      validateScene(name, args);
    }
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "linkgi-validate: %s\n", e.what());
    return 1;
  }
  return 0;
}
