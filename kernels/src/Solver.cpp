#include "linkgi/Solver.h"

#include "linkgi/Bounce.h"
#include "linkgi/DirectLight.h"
#include "linkgi/Error.h"
#include "linkgi/Links.h"
#include "linkgi/Sampling.h"

#include <chrono>
#include <cmath>
#include <cstring>

namespace linkgi
{
namespace
{
template <typename T>
bool sameArray(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), sizeof(T) * a.size()) == 0);
}

bool sameEnvironmentLayout(const Environment& a, const Environment& b)
{
  return a.hasTexture() == b.hasTexture() && a.width == b.width && a.height == b.height;
}

bool sameEnvironment(const Environment& a, const Environment& b)
{
  return sameEnvironmentLayout(a, b) && a.color == b.color && sameArray(a.texels, b.texels);
}

double msSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

/// Maps a stage's own progress in [0,1] onto [lo, hi] of the whole update.
ProgressCallback stageProgress(const ProgressCallback& progress, double lo, double hi)
{
  if (!progress)
  {
    return {};
  }
  return [&progress, lo, hi](const char* stage, double f) { return progress(stage, lo + (hi - lo) * f); };
}

/// E_env per element: the environment texels' radiance gathered through Wenv.
std::vector<Vec3f> environmentIrradiance(const SparseMatrix& wenv, const Environment& env)
{
  std::vector<Vec3f> texelRadiance;
  if (env.hasTexture())
  {
    texelRadiance.resize(env.texels.size());
    for (std::size_t i = 0; i < texelRadiance.size(); ++i)
    {
      texelRadiance[i] = env.color * env.texels[i];
    }
  }
  else
  {
    texelRadiance.push_back(env.color);
  }
  std::vector<Vec3f> irradiance(wenv.rows());
  gatherRgb(wenv, texelRadiance.data(), irradiance.data());
  return irradiance;
}
}

struct Solver::Impl
{
  // Everything below belongs to the last successful update.
  bool valid = false;
  Scene scene; // validated copy
  SolverOptions options;
  std::unique_ptr<RayTracer> tracer;
  bool tracerMatchesScene = false;
  Topology topology;
  std::vector<Vec3f> shifts, faceNormals;
  LinkStructure links;
  DirectLightResult direct;
  Solution solution;
  SolverStats stats;

  void solve(Scene scene, const SolverOptions& options, const ProgressCallback& progress);
};

Solver::Solver() : impl(std::make_unique<Impl>()) {}
Solver::~Solver() = default;

const Solution& Solver::solution() const
{
  return impl->solution;
}

const SolverStats& Solver::stats() const
{
  return impl->stats;
}

void Solver::reset()
{
  impl->valid = false;
  impl->tracerMatchesScene = false;
}

const Solution& Solver::update(const Scene& scene, const SolverOptions& options, const ProgressCallback& progress)
{
  if (options.bounces > 1000)
  {
    throw Error("The number of bounces must be at most 1000.");
  }
  if (!isPerfectSquare(options.raysPerVertex))
  {
    throw Error("The number of rays per vertex must be a perfect square (k*k, e.g. 64, 256, "
                "1024); got " + std::to_string(options.raysPerVertex) + ".");
  }
  if (!std::isfinite(options.featureAngleDegrees))
  {
    throw Error("The feature angle must be a finite number of degrees.");
  }
  impl->solve(scene, options, progress);
  return impl->solution;
}

void Solver::Impl::solve(Scene s, const SolverOptions& opt, const ProgressCallback& progress)
{
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  SolverStats st = stats; // lifetime counters carry over; per-update fields reset below
  st.builtBvh = st.refitBvh = st.builtLinks = st.builtLightLinks = st.ranBounces = false;
  st.msBvh = st.msLinks = st.msCompress = st.msLightLinks = st.msBounces = st.msSmoothing = 0;
  st.warnings = validateScene(s, opt.albedoPolicy);

  const bool topologyChanged = !valid || s.vertexCount() != scene.vertexCount() ||
    !sameArray(s.triangles, scene.triangles);
  const bool positionsChanged = topologyChanged || !sameArray(s.positions, scene.positions);
  const bool geometryChanged = positionsChanged || !sameArray(s.normals, scene.normals);
  const bool relink = geometryChanged || opt.raysPerVertex != options.raysPerVertex ||
    opt.twoSided != options.twoSided || opt.twist != options.twist || opt.seed != options.seed ||
    !sameEnvironmentLayout(s.environment, scene.environment);
  const bool relight = relink || !sameArray(s.lights, scene.lights) ||
    opt.lightOversampling != options.lightOversampling;
  const bool rebounce = relight || !sameArray(s.albedo, scene.albedo) ||
    !sameArray(s.emission, scene.emission) || !sameEnvironment(s.environment, scene.environment) ||
    opt.bounces != options.bounces || opt.smoothing != options.smoothing ||
    opt.featureAngleDegrees != options.featureAngleDegrees;
  if (!rebounce)
  {
    st.msTotal = msSince(start);
    stats = std::move(st);
    return;
  }

  // New stage results go into locals and replace the cached ones only when the whole
  // update succeeded, so an abort or error leaves the previous solution and caches intact.
  auto t = clock::now();
  if (!tracer)
  {
    tracer = createEmbreeRayTracer();
  }
  if (topologyChanged || !tracerMatchesScene)
  {
    tracerMatchesScene = false;
    tracer->build(s.positions, s.triangles);
    st.builtBvh = true;
    ++st.bvhBuilds;
  }
  else if (positionsChanged)
  {
    tracerMatchesScene = false;
    tracer->refit(s.positions);
    st.refitBvh = true;
    ++st.bvhRefits;
  }
  Topology newTopology;
  std::vector<Vec3f> newShifts, newFaceNormals;
  if (topologyChanged)
  {
    newTopology = Topology::build(s.vertexCount(), s.triangles);
  }
  const Topology& topo = topologyChanged ? newTopology : topology;
  if (geometryChanged)
  {
    newShifts = originShifts(s, topo);
    newFaceNormals = frontFaceNormals(s);
  }
  const auto& shiftsNow = geometryChanged ? newShifts : shifts;
  const auto& faceNormalsNow = geometryChanged ? newFaceNormals : faceNormals;
  st.msBvh = msSince(t);

  LinkStructure newLinks;
  if (relink)
  {
    const LinkOptions linkOptions{ opt.raysPerVertex, opt.twoSided, opt.twist, opt.seed };
    t = clock::now();
    LinkHits hits = traceLinkRays(s, shiftsNow, *tracer, linkOptions, stageProgress(progress, 0.0, 0.75));
    st.msLinks = msSince(t);
    t = clock::now();
    newLinks = compressLinks(s, hits, faceNormalsNow, linkOptions, stageProgress(progress, 0.75, 0.85));
    st.msCompress = msSince(t);
    st.builtLinks = true;
    ++st.linkBuilds;
  }
  const LinkStructure& linksNow = relink ? newLinks : links;

  DirectLightResult newDirect;
  if (relight)
  {
    t = clock::now();
    newDirect = computeDirectLight(s, topo, shiftsNow, *tracer, opt.twoSided, opt.lightOversampling,
      stageProgress(progress, 0.85, 0.95));
    st.msLightLinks = msSince(t);
    st.builtLightLinks = true;
    ++st.lightLinkBuilds;
  }
  const DirectLightResult& directNow = relight ? newDirect : direct;

  t = clock::now();
  const Elements elements{ s.vertexCount(), opt.twoSided };
  const std::size_t ne = elements.count(), nv = s.vertexCount();
  const std::vector<Vec3f> envIrradiance = environmentIrradiance(linksNow.environment, s.environment);
  BounceInputs inputs;
  inputs.fixedIrradiance.resize(ne);
  inputs.albedo.resize(ne);
  for (std::size_t e = 0; e < ne; ++e)
  {
    inputs.fixedIrradiance[e] = directNow.irradiance[e] + envIrradiance[e];
    inputs.albedo[e] = s.albedo[elements.vertexOf(e)];
  }
  if (!s.emission.empty())
  {
    // Emissive surfaces emit from their front side only.
    inputs.emission.assign(ne, Vec3f(0.f));
    std::copy(s.emission.begin(), s.emission.end(), inputs.emission.begin());
  }
  std::vector<Vec3f> indirect =
    iterateBounces(linksNow.transport, inputs, opt.bounces, stageProgress(progress, 0.95, 1.0));
  for (std::size_t e = 0; e < ne; ++e)
  {
    indirect[e] += envIrradiance[e];
  }
  st.msBounces = msSince(t);
  st.ranBounces = true;
  ++st.bounceRuns;
  if (opt.smoothing)
  {
    t = clock::now();
    const float cosFeature = std::cos(opt.featureAngleDegrees * (kPi / 180.f));
    indirect = smoothFeatureAware(indirect, topo, s.normals, elements, cosFeature);
    st.msSmoothing = msSince(t);
  }

  Solution sol;
  sol.direct = directNow.irradiance;
  sol.radiance.resize(ne);
  for (std::size_t e = 0; e < ne; ++e)
  {
    const Vec3f le = (e < nv && !s.emission.empty()) ? s.emission[e] : Vec3f(0.f);
    sol.radiance[e] = le + inputs.albedo[e] * (sol.direct[e] + indirect[e]) * (1.f / kPi);
  }
  sol.indirect = std::move(indirect);

  // Commit: nothing below can fail.
  if (topologyChanged)
  {
    topology = std::move(newTopology);
  }
  if (geometryChanged)
  {
    shifts = std::move(newShifts);
    faceNormals = std::move(newFaceNormals);
  }
  if (relink)
  {
    links = std::move(newLinks);
  }
  if (relight)
  {
    direct = std::move(newDirect);
  }
  tracerMatchesScene = true;
  scene = std::move(s);
  options = opt;
  solution = std::move(sol);
  valid = true;
  st.elements = ne;
  st.rays = links.rays;
  st.linksRaw = links.rawLinks;
  st.linksCompressed = links.transport.nonZeros();
  st.linkBytes = links.transport.bytes() + links.environment.bytes();
  st.lightRays = direct.shadowRays;
  st.msTotal = msSince(start);
  stats = std::move(st);
}
}
