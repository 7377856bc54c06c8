// The orchestrator: validation, what changed, which stages are stale, backend choice and
// fallback, progress, abort, timing and the commit - once, for every method and backend.
// It never knows a method's formulas (engine/Pipeline.h, Documentation/Engine.md).
#include "linkgi/Solver.h"

#include "engine/CudaFactory.h"
#include "engine/MemoryBudget.h"
#include "engine/Pipeline.h"

#include "cuda/Cuda.h"
#include "linkgi/Error.h"
#include "linkgi/Orientation.h"
#include "scene/BackLit.h"
#include "shared/RayTracer.h"
#include "cpu/Parallel.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <optional>

namespace linkgi
{
namespace
{
using engine::msSince;

/// sameBits on all cores for large arrays: one core compares ~7 GB/s, so the 7 MB of a
/// 121k-vertex mesh's geometry and albedo took ~1 ms of every light-only update.
template <typename T>
bool sameBitsOnAllCores(const std::vector<T>& a, const std::vector<T>& b)
{
  constexpr std::size_t kChunk = 256 << 10;
  const std::size_t bytes = a.size() * sizeof(T);
  if (a.size() != b.size() || bytes <= kChunk)
  {
    return sameBits(a, b);
  }
  const auto* x = reinterpret_cast<const unsigned char*>(a.data());
  const auto* y = reinterpret_cast<const unsigned char*>(b.data());
  std::atomic<bool> differ{ false };
  parallelRanges((bytes + kChunk - 1) / kChunk, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end && !differ.load(std::memory_order_relaxed); ++c)
    {
      const std::size_t first = c * kChunk, size = std::min(bytes, first + kChunk) - first;
      if (std::memcmp(x + first, y + first, size) != 0)
      {
        differ.store(true, std::memory_order_relaxed);
      }
    }
  });
  return !differ.load();
}

/// `to` = `from`, copied on all cores into the memory of `buffer` (an array of an update
/// before): every deformation copies the moved positions, and a fresh array page-faults
/// on every page of them first.
template <typename T>
void copyInto(std::vector<T>& to, const std::vector<T>& from, std::vector<T>& buffer)
{
  constexpr std::size_t kChunk = 256 << 10;
  to = std::move(buffer);
  buffer.clear();
  to.resize(from.size());
  const std::size_t bytes = from.size() * sizeof(T);
  auto* x = reinterpret_cast<unsigned char*>(to.data());
  const auto* y = reinterpret_cast<const unsigned char*>(from.data());
  parallelRanges((bytes + kChunk - 1) / kChunk, 1, [&](std::size_t begin, std::size_t end) {
    const std::size_t first = begin * kChunk, last = std::min(bytes, end * kChunk);
    std::memcpy(x + first, y + first, last - first);
  });
}

/// Lends the cached scene's unchanged arrays to the scene of an update (no copy), and takes
/// them back unless the update commits, so an error or abort leaves the cache whole.
class ArrayLoan
{
public:
  ArrayLoan(Scene& cache, Scene& work, const KnownValid& lent) : cache(cache), work(work), lent(lent)
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
    if (lent.positions)
    {
      to.positions = std::move(from.positions);
      to.lengthExponent = from.lengthExponent; // the scale the lent positions are in
    }
    if (lent.normals)
    {
      to.normals = std::move(from.normals);
    }
    if (lent.triangles)
    {
      to.triangles = std::move(from.triangles);
    }
    if (lent.albedo)
    {
      to.albedo = std::move(from.albedo);
    }
    if (lent.emission)
    {
      to.emission = std::move(from.emission);
    }
  }

  Scene& cache;
  Scene& work;
  const KnownValid lent;
  bool committed = false;
};

/// The input's arrays that equal the cached scene's, each compared once on all cores: those
/// are lent, not copied, and not validated again.
KnownValid unchangedArrays(const Scene& input, const Scene& cached)
{
  KnownValid same;
  same.positions = sameBitsOnAllCores(input.positions, cached.positions);
  // Triangles were checked against the cached vertex count.
  same.triangles = input.vertexCount() == cached.vertexCount() && sameBitsOnAllCores(input.triangles, cached.triangles);
  same.normals = sameBitsOnAllCores(input.normals, cached.normals);
  same.albedo = sameBitsOnAllCores(input.albedo, cached.albedo);
  same.emission = sameBitsOnAllCores(input.emission, cached.emission);
  return same;
}

/// Copies into `s` what `lent` does not lend of `input`; moved positions and normals into
/// the buffers of `spare`.
void copyChanged(const Scene& input, const KnownValid& lent, Scene& s, Scene& spare)
{
  if (!lent.positions)
  {
    copyInto(s.positions, input.positions, spare.positions);
    s.lengthExponent = input.lengthExponent;
  }
  if (!lent.normals)
  {
    copyInto(s.normals, input.normals, spare.normals);
  }
  if (!lent.triangles)
  {
    s.triangles = input.triangles;
  }
  if (!lent.albedo)
  {
    s.albedo = input.albedo;
  }
  if (!lent.emission)
  {
    s.emission = input.emission;
  }
  s.triangleMaterials = input.triangleMaterials;
  s.triangleIor = input.triangleIor;
  s.lights = input.lights;
  s.environment = input.environment;
}

/// One backend's implementation of the current method, and whether its caches follow the
/// last committed update.
struct BackendSlot
{
  std::unique_ptr<engine::MethodBackend> impl;
  bool synced = false;
  Method method = Method::Links;
  int cudaDevices = 0;

  bool fits(const SolverOptions& o, bool cuda) const
  {
    return impl && method == o.method && (!cuda || cudaDevices == o.cudaDevices);
  }
};

/// Fresh per-update records of the method's stages; lifetime run counts carry over.
std::vector<StageStats> stageRecords(const engine::MethodSpec& spec, const SolverStats& before)
{
  std::vector<StageStats> records;
  for (const engine::StageSpec& s : spec.stages())
  {
    StageStats r;
    r.name = s.name;
    r.counter = s.counter;
    const StageStats* old = before.stage(s.name);
    r.runs = old && before.method == spec.name() ? old->runs : 0;
    records.push_back(std::move(r));
  }
  return records;
}
}

struct Solver::Impl
{
  // Everything below belongs to the last successful update.
  bool valid = false;
  // The last update's validated input. reset() forgets the stages, not this: validation is
  // a function of the input alone, so equal input arrays need not be copied and checked
  // again (a full update after reset() on conference: 5.3 ms less on the host).
  Scene scene;
  bool validated = false;
  SolverOptions options;
  Solution solution;
  SolverStats stats;
  Solution spare; // the solution before last: its buffers are reused by the next update
  Scene spareArrays; // positions and normals before last: a deformation copies into them

  BackendSlot cpu, cuda;
  int cudaDevicesFound = 0; // GPUs the CUDA backend was made for
  // The committed scene's surfaces (surfaceLabels), for the orientation checks.
  std::vector<Index> surfaceOf;
  std::size_t surfaces = 0;

  void solve(const Scene& input, const SolverOptions& options, const ProgressCallback& progress);
  /// Warns about the sides of a one-sided result (warnsAboutSides): fronts in the shadow of
  /// their own surface, and surfaces lit only on their backs (with `tracer` over `s`).
  void checkSides(const Scene& s, const Solution& sol, const SolverOptions& opt, engine::Changes changes,
    const RayTracer* tracer, std::vector<std::string>& warnings);
  bool chooseCuda(const engine::MethodSpec& spec, const SolverOptions& opt, SolverStats& st);
  void runStages(BackendSlot& slot, bool onCuda, const engine::MethodSpec& spec,
    engine::Changes changes, const Scene& s, const SolverOptions& opt, Solution& sol,
    SolverStats& st, const ProgressCallback& progress);
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
  impl->cpu.synced = impl->cuda.synced = false;
}

const Solution& Solver::update(const Scene& scene, const SolverOptions& options, const ProgressCallback& progress)
{
  validateOptions(options);
  impl->solve(scene, options, progress);
  return impl->solution;
}

bool Solver::Impl::chooseCuda(const engine::MethodSpec& spec, const SolverOptions& opt, SolverStats& st)
{
  if (opt.backend == Backend::Cpu)
  {
    st.backendNote = "CPU requested.";
    return false;
  }
  const engine::CudaFactory& factory = engine::cudaFactory();
  if (factory.has && !factory.has(spec))
  {
    const std::string why = std::string("the method '") + spec.name() + "' has no CUDA backend; using the CPU.";
    if (opt.backend == Backend::Cuda)
    {
      st.warnings.push_back("CUDA requested, but " + why);
    }
    st.backendNote = std::string(opt.backend == Backend::Auto ? "Auto" : "CUDA requested") + ": " + why;
    return false;
  }
  if (opt.partition)
  {
    // Every process must take the same path through the partition's collective exchanges:
    // one falling back from the GPU alone would leave the others waiting.
    st.backendNote = "A partitioned solve runs on the CPU.";
    return false;
  }
  const std::string who = opt.backend == Backend::Auto ? "Auto" : "CUDA requested";
  if (cuda.fits(opt, true))
  {
    // The devices were found when the backend was made (asking again costs milliseconds).
    st.backendNote = who + ": " + std::to_string(cudaDevicesFound) + " CUDA device(s) in use; using the GPU.";
    return true;
  }
  std::string why;
  const std::size_t found = factory.devices(&why);
  if (found == 0)
  {
    if (opt.backend == Backend::Cuda)
    {
      st.warnings.push_back("CUDA backend not available in this build; using the CPU (" + why + ").");
    }
    st.backendNote = who + ": " + why + "; using the CPU.";
    return false;
  }
  cudaDevicesFound = int(opt.cudaDevices > 0 ? std::min<std::size_t>(found, opt.cudaDevices) : found);
  st.backendNote = who + ": " + std::to_string(found) + " CUDA device(s) found; using the GPU.";
  return true;
}

void Solver::Impl::runStages(BackendSlot& slot, bool onCuda, const engine::MethodSpec& spec,
  engine::Changes changes, const Scene& s, const SolverOptions& opt, Solution& sol,
  SolverStats& st, const ProgressCallback& progress)
{
  // A backend that is made anew, or whose caches do not follow the committed scene, runs
  // every stage; the budget is checked before the old backend's memory is given up.
  const engine::Changes seen = slot.fits(opt, onCuda) && slot.synced ? changes : engine::kEverything;
  const std::uint32_t stale = engine::staleStages(spec.stages(), seen);
  // A method that samples a stage's memory (on the CPU) is judged for the stages before it
  // first, and for all of them before that stage, with what it sampled: the solution is
  // written by the last stage only, so a refusal there keeps the previous result too. Under
  // MPI each process samples and judges its own rows (engine/MemoryBudget.h).
  const int sampled = onCuda ? -1 : spec.memorySampleStage();
  const bool samples = sampled >= 0 && (stale >> sampled & 1u);
  MemoryShape shape = MemoryShape::of(s);
  engine::checkMemoryBudget(spec, shape, opt, stale, onCuda, st, samples ? (1u << sampled) - 1u : ~0u);
  if (!slot.fits(opt, onCuda))
  {
    slot.impl.reset(); // frees the old one's memory before the new one allocates
    slot.synced = false;
    slot.impl = onCuda ? engine::cudaFactory().create(spec, opt) : spec.createCpu(opt);
    slot.method = opt.method;
    slot.cudaDevices = opt.cudaDevices;
  }
  const std::vector<engine::StageSpec>& stages = spec.stages();
  double shareSum = 0.0, shareDone = 0.0;
  for (std::size_t i = 0; i < stages.size(); ++i)
  {
    shareSum += (stale >> i & 1u) ? stages[i].progressShare : 0.0;
  }
  st.stages = stageRecords(spec, st);
  const bool wasSynced = slot.synced;
  slot.synced = false; // until this update has committed
  try
  {
    for (std::size_t i = 0; i < stages.size(); ++i)
    {
      if (!(stale >> i & 1u))
      {
        continue;
      }
      const double lo = shareDone / shareSum, hi = (shareDone += stages[i].progressShare) / shareSum;
      ProgressCallback window;
      if (progress)
      {
        window = [&progress, lo, hi](const char* stage, double f) { return progress(stage, lo + (hi - lo) * f); };
      }
      const engine::StageContext context(s, opt, seen, std::move(window), sol, st, stages[i].name);
      const std::size_t partsBefore = st.stages.size();
      const auto start = std::chrono::steady_clock::now();
      context.check(0.0);
      if (samples && int(i) == sampled)
      {
        shape.sampledPerElement = slot.impl->sampleMemory(context);
        context.part("MemorySample", msSince(start));
        engine::checkMemoryBudget(spec, shape, opt, stale, onCuda, st);
      }
      slot.impl->run(i, context);
      double ms = msSince(start);
      for (std::size_t p = partsBefore; p < st.stages.size(); ++p)
      {
        ms -= st.stages[p].ms;
      }
      st.stages[i].ran = true;
      st.stages[i].ms = ms;
    }
  }
  catch (...)
  {
    // Caches that followed an older commit (another backend ran since) stay unusable even
    // when the failed update left them alone.
    slot.synced = slot.impl->discard() && wasSynced;
    throw;
  }
  slot.impl->commit();
  slot.synced = true;
  for (StageStats& r : st.stages)
  {
    r.runs += r.ran && r.parent.empty();
  }
  slot.impl->describe(st);
}

namespace
{
/// Below this share of the light that faces the fronts reaching them (litShareOfFronts), a
/// one-sided scene is warned about: inside-out surfaces give 0-2% (an inside-out tube, the
/// Utah teapot as PyVista's data has it), the standard scenes, the scanned models in their
/// rooms, the dining room and 23 models alone 33-100% (Documentation/Guide.md).
constexpr float kShadowedFronts = 0.05f;

/// Whether the sides of the scene's surfaces are checked: one-sided, lit by its lights alone
/// (no emission, a black sky), whose light the direct irradiance holds.
bool warnsAboutSides(const Scene& s, const SolverOptions& o)
{
  const bool emits = std::any_of(s.emission.begin(), s.emission.end(), [](const Vec3f& e) { return maxComponent(e) > 0.f; });
  return !o.twoSided && !s.lights.empty() && !emits && s.environment.isBlack();
}

/// From this share of the triangles on, surfaces lit only on their backs while others are lit
/// in front are warned about: polygons of mixed orientation (GIS data) and an inside-out open
/// part give about half; small parts of scanned and CAD models, whose backs see a light
/// through the models' holes, at most 4% (Documentation/Guide.md).
constexpr double kBackLitTriangles = 0.1;

/// The warning for surfaces that the lights reach only on their backs while others are lit
/// in front (litOnlyOnTheirBacks), where they hold kBackLitTriangles of the triangles.
std::string backLitWarning(const LitOnTheirBacks& r)
{
  if (r.frontLit == 0 || r.surfaces == 0 || double(r.triangles) < kBackLitTriangles * double(r.knownTriangles))
  {
    return {};
  }
  return std::to_string(r.surfaces) + " of " + std::to_string(r.surfaces + r.frontLit) + " lit surfaces (" +
    std::to_string(r.triangles) + " triangles) are lit only on their backs (the sides their normals point away "
    "from), which a one-sided solution leaves dark. Where their winding is reversed (polygons of mixed "
    "orientation, as GIS data has them) or a sheet faces away from the lights, turn TwoSided on to light both "
    "sides, or reverse those cells (vtkReverseSense).";
}

/// The warning for a scene whose fronts that face the lights lie almost all in shadow;
/// empty otherwise.
std::string shadowedFrontsWarning(const Scene& s, const Solution& sol)
{
  const float share = litShareOfFronts(s, sol.direct);
  if (share >= kShadowedFronts)
  {
    return {};
  }
  const int blocked = int(std::lround(100.0 * (1.0 - share)));
  return "Shadows block " + std::to_string(blocked) + "% of the light that faces the surfaces' front sides "
    "(the sides their normals point to, the only ones LinkGI lights). A surface wound inside out, open or "
    "closed, looks so: its fronts face its inside, in the shadow of its near wall. Reverse its normals "
    "(vtkReverseSense, or vtkPolyDataNormals with AutoOrientNormalsOn for a closed one), or turn TwoSided on "
    "to light both sides.";
}
}

void Solver::Impl::checkSides(const Scene& s, const Solution& sol, const SolverOptions& opt,
  engine::Changes changes, const RayTracer* tracer, std::vector<std::string>& warnings)
{
  if (!warnsAboutSides(s, opt))
  {
    return;
  }
  std::string shadowed = shadowedFrontsWarning(s, sol);
  if (!shadowed.empty())
  {
    warnings.push_back(std::move(shadowed));
  }
  if (!tracer)
  {
    return;
  }
  if ((changes & engine::kTopology) || surfaceOf.size() != s.vertexCount())
  {
    surfaceOf = surfaceLabels(s, surfaces);
  }
  try
  {
    std::string backs = backLitWarning(litOnlyOnTheirBacks(s, surfaceOf, surfaces, sol.direct, *tracer));
    if (!backs.empty())
    {
      warnings.push_back(std::move(backs));
    }
  }
  catch (const CudaError& e)
  {
    // The result stands; only its check through the GPU's BVH is lost.
    warnings.push_back(std::string("Which surfaces are lit only on their backs was not checked: the GPU failed (") +
      e.what() + ").");
  }
}

void Solver::Impl::solve(const Scene& input, const SolverOptions& opt, const ProgressCallback& progress)
{
  const auto start = std::chrono::steady_clock::now();
  SolverStats st = stats; // lifetime counters carry over; per-update fields reset here
  st.builtBvh = st.refitBvh = false;
  st.stages.erase(std::remove_if(st.stages.begin(), st.stages.end(),
                    [](const StageStats& r) { return !r.parent.empty(); }),
    st.stages.end());
  for (StageStats& r : st.stages)
  {
    r.ran = false;
    r.ms = 0.0;
  }

  // Unchanged arrays are neither copied nor validated again: the cached ones passed
  // validation unchanged, so equal input arrays would too. A light or material change on a
  // large mesh then costs no more host time than comparing the arrays; a deformation adds
  // the copy and the checks of what moved (4-8 ms on one core for conference's whole scene,
  // which the GPU's deformation step waited for).
  KnownValid lent = validated ? unchangedArrays(input, scene) : KnownValid{};
  Scene s;
  std::optional<ArrayLoan> loan;
  loan.emplace(scene, s, lent);
  copyChanged(input, lent, s, spareArrays);
  if (!validateChanges(s, opt.albedoPolicy, lent, st.warnings))
  {
    // The moved positions made a lent triangle degenerate: validate a copy of them, which
    // loses it.
    loan.reset();
    s = Scene();
    lent.triangles = false;
    loan.emplace(scene, s, lent);
    copyChanged(input, lent, s, spareArrays);
    validateChanges(s, opt.albedoPolicy, lent, st.warnings);
  }

  const bool sameMaterials =
    sameBits(input.triangleMaterials, scene.triangleMaterials) && sameBits(input.triangleIor, scene.triangleIor);
  const auto knownIf = [](bool same, engine::Changes bit) { return same ? bit : engine::Changes(0); };
  const engine::Changes knownSame = knownIf(lent.triangles, engine::kTopology) |
    knownIf(lent.positions, engine::kPositions) | knownIf(lent.normals, engine::kNormals) |
    knownIf(lent.albedo && sameMaterials, engine::kAlbedo) | knownIf(lent.emission, engine::kEmission);
  const engine::Changes changes =
    valid ? engine::changesBetween(s, opt, scene, options, knownSame) : engine::kEverything;
  st.msPrepare = msSince(start);
  if (changes == 0)
  {
    st.msTotal = msSince(start);
    stats = std::move(st);
    return;
  }
  st.counters.clear(); // the backend that runs reports its method's own

  // New results go into `sol` and the backend's staging, and replace the cached ones only
  // when the whole update succeeded, so an abort or error leaves the previous solution.
  const engine::MethodSpec& spec = engine::methodSpec(opt.method);
  if (!spec.carriesSpecular() && s.hasSpecular())
  {
    st.warnings.push_back(std::string("The ") + spec.name() + " method lights mirror and glass "
      "triangles as diffuse surfaces; photon-mapping carries light through them.");
  }
  Solution sol = std::move(spare); // same sizes as a rule: no allocation, no page faults
  spare = Solution();
  sol.caustics.clear(); // only a method that makes caustics fills it
  bool ran = false, onCpu = false;
  if (chooseCuda(spec, opt, st))
  {
    try
    {
      runStages(cuda, true, spec, changes, s, opt, sol, st, progress);
      cpu.synced = false; // the CPU's caches no longer follow the committed scene
      ran = true;
    }
    catch (const CudaError& e)
    {
      // Out of memory, a device that vanished, a kernel fault: the CPU takes over.
      cuda.impl.reset();
      st.warnings.push_back(std::string("The CUDA backend failed (") + e.what() + "); using the CPU.");
      st.backendNote = "CUDA failed; using the CPU.";
    }
  }
  if (!ran)
  {
    runStages(cpu, false, spec, changes, s, opt, sol, st, progress);
    cuda.synced = false;
    onCpu = true;
  }

  checkSides(s, sol, opt, changes, (onCpu ? cpu : cuda).impl->sceneTracer(), st.warnings);

  // Commit: nothing below can fail.
  loan->commit();
  if (!lent.positions)
  {
    spareArrays.positions = std::move(scene.positions);
  }
  if (!lent.normals)
  {
    spareArrays.normals = std::move(scene.normals);
  }
  scene = std::move(s);
  options = opt;
  spare = std::move(solution);
  solution = std::move(sol);
  valid = validated = true;
  st.method = spec.name();
  st.elements = solution.elementCount();
  st.msTotal = msSince(start);
  stats = std::move(st);
}
}
