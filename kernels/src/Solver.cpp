#include "linkgi/Solver.h"

#include "linkgi/Bounce.h"
#include "linkgi/Cuda.h"
#include "linkgi/DirectLight.h"
#include "linkgi/Error.h"
#include "linkgi/Links.h"
#include "linkgi/Sampling.h"

#if LINKGI_HAVE_CUDA
#include "cuda/CudaEngine.h"
#endif

#include <chrono>
#include <cmath>
#include <cstring>

namespace linkgi
{
namespace
{
/// Bitwise equality. One thread: on the 16-core GPU machine splitting the comparison over
/// the thread pool measured twice as slow as a single memcmp of conference's 8 MB.
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

/// What an update must redo, relative to the last successful one.
struct Changes
{
  bool topology = true, positions = true, geometry = true, relink = true, relight = true,
       materials = true, rebounce = true;
};

/// Lends the cached scene's unchanged arrays to the scene of an update (no copy), and takes
/// them back unless the update commits, so an error or abort leaves the cache whole.
class ArrayLoan
{
public:
  ArrayLoan(Scene& cache, Scene& work, bool geometry, bool albedo, bool emission)
    : cache(cache), work(work), geometry(geometry), albedo(albedo), emission(emission)
  {
    move(cache, work);
  }
  ~ArrayLoan()
  {
    if (!committed)
    {
      move(work, cache);
    }
  }
  ArrayLoan(const ArrayLoan&) = delete;
  ArrayLoan& operator=(const ArrayLoan&) = delete;
  void commit() { committed = true; }

private:
  void move(Scene& from, Scene& to) const
  {
    if (geometry)
    {
      to.positions = std::move(from.positions);
      to.normals = std::move(from.normals);
      to.triangles = std::move(from.triangles);
    }
    if (albedo)
    {
      to.albedo = std::move(from.albedo);
    }
    if (emission)
    {
      to.emission = std::move(from.emission);
    }
  }

  Scene& cache;
  Scene& work;
  bool geometry, albedo, emission;
  bool committed = false;
};

/// Which of the input's arrays equal the cached (validated) scene's, and are lent from it.
struct Lent
{
  bool geometry = false, albedo = false, emission = false;
};

/// The host-side geometry data both backends read: new where the geometry changed.
struct HostGeometry
{
  const Topology* topology = nullptr;
  const std::vector<Vec3f>* shifts = nullptr;
  const std::vector<Vec3f>* faceNormals = nullptr;
};
}

struct Solver::Impl
{
  // Everything below belongs to the last successful update.
  bool valid = false;
  Scene scene; // validated copy
  SolverOptions options;
  Topology topology;
  std::vector<Vec3f> shifts, faceNormals;
  Solution solution;
  SolverStats stats;

  // CPU backend caches; valid for `scene` only if cpuValid.
  bool cpuValid = false;
  std::unique_ptr<RayTracer> tracer;
  bool tracerMatchesScene = false;
  LinkStructure links;
  DirectLightResult direct;
  LinkHits hitScratch; // link rays' hits, kept so the next relink reuses the buffer

#if LINKGI_HAVE_CUDA
  // CUDA backend; its device caches are valid for `scene` only if cudaValid.
  std::unique_ptr<cuda::Engine> engine;
  int engineDevices = -1;
  bool cudaValid = false;
#endif

  Solution spare; // the solution before last: its buffers are reused by the next update

  void solve(const Scene& input, const SolverOptions& options, const ProgressCallback& progress);
  Changes detect(const Scene& s, const SolverOptions& opt, const Lent& lent) const;
  Backend choose(const SolverOptions& opt, SolverStats& st);
  void solveCpu(const Scene& s, const SolverOptions& opt, Changes c, const HostGeometry& g,
    Solution& sol, SolverStats& st, const ProgressCallback& progress);
  bool solveCuda(const Scene& s, const SolverOptions& opt, const Changes& c,
    const HostGeometry& g, Solution& sol, SolverStats& st, const ProgressCallback& progress);
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
  impl->cpuValid = false;
  impl->tracerMatchesScene = false;
#if LINKGI_HAVE_CUDA
  impl->cudaValid = false;
#endif
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

Changes Solver::Impl::detect(const Scene& s, const SolverOptions& opt, const Lent& lent) const
{
  // Lent arrays are the cached ones (the cache's own are empty meanwhile); the others are
  // compared after validation, as validation may have repaired them.
  Changes c;
  c.topology = !lent.geometry &&
    (!valid || s.vertexCount() != scene.vertexCount() || !sameArray(s.triangles, scene.triangles));
  c.positions = c.topology || (!lent.geometry && !sameArray(s.positions, scene.positions));
  c.geometry = c.positions || (!lent.geometry && !sameArray(s.normals, scene.normals));
  c.relink = c.geometry || opt.raysPerVertex != options.raysPerVertex ||
    opt.twoSided != options.twoSided || opt.twist != options.twist || opt.seed != options.seed ||
    !sameEnvironmentLayout(s.environment, scene.environment);
  c.relight = c.relink || !sameArray(s.lights, scene.lights) ||
    opt.lightOversampling != options.lightOversampling;
  c.materials = c.topology || (!lent.albedo && !sameArray(s.albedo, scene.albedo)) ||
    (!lent.emission && !sameArray(s.emission, scene.emission));
  c.rebounce = c.relight || c.materials || !sameEnvironment(s.environment, scene.environment) ||
    opt.bounces != options.bounces || opt.smoothing != options.smoothing ||
    opt.featureAngleDegrees != options.featureAngleDegrees;
  return c;
}

Backend Solver::Impl::choose(const SolverOptions& opt, SolverStats& st)
{
  if (opt.backend == Backend::Cpu)
  {
    st.backendNote = "CPU requested.";
    return Backend::Cpu;
  }
#if LINKGI_HAVE_CUDA
  if (engine && engineDevices == opt.cudaDevices)
  {
    // The devices were found when the engine was made (asking again costs milliseconds).
    st.backendNote = std::string(opt.backend == Backend::Auto ? "Auto: " : "CUDA requested: ") +
      std::to_string(engine->deviceCount()) + " CUDA device(s) in use; using the GPU.";
    return Backend::Cuda;
  }
#endif
  std::string why;
  const std::vector<cuda::DeviceInfo> gpus = cuda::devices(&why);
  if (gpus.empty())
  {
    if (opt.backend == Backend::Cuda)
    {
      st.warnings.push_back("CUDA backend not available in this build; using the CPU (" + why + ").");
    }
    st.backendNote = std::string(opt.backend == Backend::Auto ? "Auto" : "CUDA requested") +
      ": " + why + "; using the CPU.";
    return Backend::Cpu;
  }
  st.backendNote = std::string(opt.backend == Backend::Auto ? "Auto: " : "CUDA requested: ") +
    std::to_string(gpus.size()) + " CUDA device(s) found; using the GPU.";
  return Backend::Cuda;
}

void Solver::Impl::solve(const Scene& input, const SolverOptions& opt, const ProgressCallback& progress)
{
  const auto start = std::chrono::steady_clock::now();
  SolverStats st = stats; // lifetime counters carry over; per-update fields reset below
  st.builtBvh = st.refitBvh = st.builtLinks = st.builtLightLinks = st.ranBounces = false;
  st.msBvh = st.msLinks = st.msCompress = st.msLightLinks = st.msBounces = st.msSmoothing = 0;

  // Unchanged arrays are neither copied nor validated again: the cached ones passed
  // validation unchanged, so equal input arrays would too. A light or material change on
  // a large mesh then costs no more host time than comparing the arrays.
  Lent lent;
  lent.geometry = valid && sameArray(input.positions, scene.positions) &&
    sameArray(input.normals, scene.normals) && sameArray(input.triangles, scene.triangles);
  lent.albedo = lent.geometry && sameArray(input.albedo, scene.albedo);
  lent.emission = lent.geometry && sameArray(input.emission, scene.emission);
  Scene s;
  ArrayLoan loan(scene, s, lent.geometry, lent.albedo, lent.emission);
  if (lent.geometry)
  {
    if (!lent.albedo)
    {
      s.albedo = input.albedo;
    }
    if (!lent.emission)
    {
      s.emission = input.emission;
    }
    s.lights = input.lights;
    s.environment = input.environment;
    st.warnings = validateShading(s, opt.albedoPolicy, lent.albedo, lent.emission);
  }
  else
  {
    s = input;
    st.warnings = validateScene(s, opt.albedoPolicy);
  }

  const Changes c = detect(s, opt, lent);
  st.msPrepare = msSince(start);
  const bool sameBackend = opt.backend == options.backend && opt.cudaDevices == options.cudaDevices &&
    opt.cudaBvhBuild == options.cudaBvhBuild;
  if (!c.rebounce && sameBackend)
  {
    st.msTotal = msSince(start);
    stats = std::move(st);
    return;
  }

  // New results go into locals and replace the cached ones only when the whole update
  // succeeded, so an abort or error leaves the previous solution and caches intact.
  auto t = std::chrono::steady_clock::now();
  Topology newTopology;
  std::vector<Vec3f> newShifts, newFaceNormals;
  if (c.topology)
  {
    newTopology = Topology::build(s.vertexCount(), s.triangles);
  }
  const Topology& topo = c.topology ? newTopology : topology;
  if (c.geometry)
  {
    newShifts = originShifts(s, topo);
    newFaceNormals = frontFaceNormals(s);
  }
  const HostGeometry g{ &topo, c.geometry ? &newShifts : &shifts,
    c.geometry ? &newFaceNormals : &faceNormals };
  const double msHost = msSince(t);
  st.msTopology = msHost;

  Solution sol = std::move(spare); // same sizes as a rule: no allocation, no page faults
  spare = Solution();
  const Backend backend = choose(opt, st);
  if (backend != Backend::Cuda || !solveCuda(s, opt, c, g, sol, st, progress))
  {
    solveCpu(s, opt, c, g, sol, st, progress);
  }
  st.msBvh += msHost;

  // Commit: nothing below can fail.
  if (c.topology)
  {
    topology = std::move(newTopology);
  }
  if (c.geometry)
  {
    shifts = std::move(newShifts);
    faceNormals = std::move(newFaceNormals);
  }
  loan.commit();
  scene = std::move(s);
  options = opt;
  spare = std::move(solution);
  solution = std::move(sol);
  valid = true;
  st.elements = solution.elementCount();
  st.msTotal = msSince(start);
  stats = std::move(st);
}

bool Solver::Impl::solveCuda(const Scene& s, const SolverOptions& opt, const Changes& c,
  const HostGeometry& g, Solution& sol, SolverStats& st, const ProgressCallback& progress)
{
#if LINKGI_HAVE_CUDA
  try
  {
    if (opt.raysPerVertex > cuda::kMaxCompressRays)
    {
      throw CudaError("the CUDA backend merges at most " + std::to_string(cuda::kMaxCompressRays) +
          " rays per vertex",
        false);
    }
    if (!engine || engineDevices != opt.cudaDevices)
    {
      engine.reset();
      cudaValid = false;
      engine = std::make_unique<cuda::Engine>(opt.cudaDevices);
      engineDevices = opt.cudaDevices;
    }
    const bool all = !cudaValid || opt.cudaBvhBuild != options.cudaBvhBuild;
    cuda::StageMask mask;
    mask.topology = all || c.topology;
    mask.positions = all || c.positions;
    mask.geometry = all || c.geometry;
    mask.relink = all || c.relink;
    mask.relight = all || c.relight;
    mask.materials = all || c.materials;
    cudaValid = false; // until this update has succeeded
    engine->update(cuda::HostInputs{ s, *g.topology, *g.shifts, *g.faceNormals }, opt, mask, sol,
      st, progress);
    cudaValid = true;
    cpuValid = false; // the CPU's caches no longer follow the scene
    tracerMatchesScene = false;
    st.backend = "cuda";
    st.device = engine->description();
    st.devices = engine->deviceCount();
    const std::vector<std::size_t> linked = engine->linkedElements();
    st.linkedPerDevice.assign(linked.begin(), linked.end());
    engine->linkProfile(st);
    st.gpuPeakBytes = engine->peakBytes();
    return true;
  }
  catch (const CudaError& e)
  {
    // Out of memory, a device that vanished, a kernel fault: the CPU takes over.
    engine.reset();
    st.warnings.push_back(std::string("The CUDA backend failed (") + e.what() + "); using the CPU.");
    st.backendNote = "CUDA failed; using the CPU.";
    return false;
  }
#else
  (void)s, (void)opt, (void)c, (void)g, (void)sol, (void)st, (void)progress;
  return false;
#endif
}

void Solver::Impl::solveCpu(const Scene& s, const SolverOptions& opt, Changes c,
  const HostGeometry& g, Solution& sol, SolverStats& st, const ProgressCallback& progress)
{
  using clock = std::chrono::steady_clock;
  if (!cpuValid)
  {
    c.relink = c.relight = true; // the caches belong to an older scene (the GPU ran since)
  }
  auto t = clock::now();
  if (!tracer)
  {
    tracer = createCpuRayTracer();
  }
  if (c.topology || !tracerMatchesScene)
  {
    tracerMatchesScene = false;
    tracer->build(s.positions, s.triangles);
    st.builtBvh = true;
    ++st.bvhBuilds;
  }
  else if (c.positions)
  {
    tracerMatchesScene = false;
    tracer->refit(s.positions);
    st.refitBvh = true;
    ++st.bvhRefits;
  }
  st.msBvh = msSince(t);

  LinkStructure newLinks;
  if (c.relink)
  {
    const LinkOptions linkOptions{ opt.raysPerVertex, opt.twoSided, opt.twist, opt.seed };
    t = clock::now();
    traceLinkRays(s, *g.shifts, *tracer, linkOptions, hitScratch, stageProgress(progress, 0.0, 0.75));
    st.msLinks = msSince(t);
    t = clock::now();
    newLinks = compressLinks(s, hitScratch, *g.faceNormals, linkOptions, stageProgress(progress, 0.75, 0.85));
    st.msCompress = msSince(t);
    st.builtLinks = true;
    ++st.linkBuilds;
  }
  const LinkStructure& linksNow = c.relink ? newLinks : links;

  DirectLightResult newDirect;
  if (c.relight)
  {
    t = clock::now();
    newDirect = computeDirectLight(s, *g.topology, *g.shifts, *tracer, opt.twoSided,
      opt.lightOversampling, stageProgress(progress, 0.85, 0.95));
    st.msLightLinks = msSince(t);
    st.builtLightLinks = true;
    ++st.lightLinkBuilds;
  }
  const DirectLightResult& directNow = c.relight ? newDirect : direct;

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
    indirect = smoothFeatureAware(indirect, *g.topology, s.normals, elements, cosFeature);
    st.msSmoothing = msSince(t);
  }

  sol.direct = directNow.irradiance;
  sol.radiance.resize(ne);
  for (std::size_t e = 0; e < ne; ++e)
  {
    const Vec3f le = (e < nv && !s.emission.empty()) ? s.emission[e] : Vec3f(0.f);
    sol.radiance[e] = outgoingRadiance(inputs.albedo[e], sol.direct[e], indirect[e], le);
  }
  sol.indirect = std::move(indirect);

  // Commit the CPU caches (the update cannot fail after this point).
  if (c.relink)
  {
    links = std::move(newLinks);
  }
  if (c.relight)
  {
    direct = std::move(newDirect);
  }
  tracerMatchesScene = true;
  cpuValid = true;
#if LINKGI_HAVE_CUDA
  cudaValid = false; // the GPU's caches no longer follow `scene`
#endif
  st.backend = "cpu";
  st.device = tracer->name();
  st.devices = 0;
  st.linkedPerDevice.clear();
  st.gpuPeakBytes = 0;
  st.rays = links.rays;
  st.linksRaw = links.rawLinks;
  st.linksCompressed = links.transport.nonZeros();
  st.linkBytes = links.transport.bytes() + links.environment.bytes();
  st.lightRays = direct.shadowRays;
}
}
