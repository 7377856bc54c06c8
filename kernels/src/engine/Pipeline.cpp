#include "engine/Pipeline.h"
#include "engine/Methods.h"

#include "cuda/Cuda.h"
#include "linkgi/Error.h"
#include "shared/Sampling.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace linkgi
{
namespace
{
/// Whether any method's own options differ (MethodSpec::optionsDiffer).
bool methodOptionsDiffer(const SolverOptions& a, const SolverOptions& b)
{
  for (const engine::MethodEntry& entry : engine::methodTable())
  {
    if (entry.spec().optionsDiffer(a, b))
    {
      return true;
    }
  }
  return false;
}
}

bool operator==(const SolverOptions& a, const SolverOptions& b)
{
  return a.method == b.method && a.raysPerVertex == b.raysPerVertex && a.bounces == b.bounces &&
    a.smoothing == b.smoothing && a.featureAngleDegrees == b.featureAngleDegrees &&
    a.twoSided == b.twoSided && a.twist == b.twist && a.seed == b.seed &&
    a.lightOversampling == b.lightOversampling && a.albedoPolicy == b.albedoPolicy &&
    a.backend == b.backend && a.cudaDevices == b.cudaDevices &&
    a.cudaBvhUpdate == b.cudaBvhUpdate && a.cudaBvhBuild == b.cudaBvhBuild &&
    a.memoryBudget == b.memoryBudget && a.partition == b.partition && !methodOptionsDiffer(a, b);
}

void validateOptions(const SolverOptions& options)
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
  if (options.cudaDevices < 0)
  {
    throw Error("The number of CUDA devices must be 0 (all) or more; got " +
      std::to_string(options.cudaDevices) + ".");
  }
  // Every method's own options, not only the chosen one's: a bad value is refused where it
  // is set, not when the method is switched to later.
  for (const engine::MethodEntry& entry : engine::methodTable())
  {
    entry.spec().validateOptions(options);
  }
  engine::methodSpec(options.method).checkCombination(options);
}

std::uint64_t SolverStats::counter(const std::string& name) const
{
  for (const auto& c : counters)
  {
    if (c.first == name)
    {
      return c.second;
    }
  }
  return 0;
}

void SolverStats::setCounter(const std::string& name, std::uint64_t value)
{
  for (auto& c : counters)
  {
    if (c.first == name)
    {
      c.second = value;
      return;
    }
  }
  counters.emplace_back(name, value);
}

const StageStats* SolverStats::stage(const std::string& name) const
{
  for (const StageStats& s : stages)
  {
    if (s.name == name)
    {
      return &s;
    }
  }
  return nullptr;
}

bool SolverStats::ran(const std::string& name) const
{
  const StageStats* s = stage(name);
  return s && s->ran;
}

double SolverStats::ms(const std::string& name) const
{
  const StageStats* s = stage(name);
  return s ? s->ms : 0.0;
}

std::uint64_t SolverStats::runs(const std::string& counter) const
{
  for (const StageStats& s : stages)
  {
    if (s.counter == counter || (s.parent.empty() && s.name == counter))
    {
      return s.runs;
    }
  }
  return 0;
}

void Partition::check() const
{
  const std::uint64_t failures = count ? count(0) : 0;
  if (failures > 0)
  {
    throw PeerFailed(failures);
  }
}

void Partition::fail() const
{
  if (count)
  {
    count(1);
  }
}

void Partition::exchange(std::vector<Vec3f>& values) const
{
  check();
  sum(values);
}

std::uint64_t Partition::smallest(std::uint64_t value) const
{
  check();
  return least ? least(value) : value;
}

void together(const Partition* partition, const std::function<void()>& work)
{
  if (!partition)
  {
    work();
    return;
  }
  try
  {
    work();
  }
  catch (const PeerFailed&)
  {
    throw; // learnt in an agreement step: every process knows already
  }
  catch (...)
  {
    partition->fail();
    throw;
  }
  partition->check();
}

namespace engine
{
std::unique_ptr<MethodBackend> MethodSpec::createCuda(const SolverOptions&) const
{
  if (!cuda::compiled())
  {
    throw CudaError("This build has no CUDA backend; reconfigure with LINKGI_ENABLE_CUDA=ON.", false);
  }
  throw CudaError(std::string("The method '") + name() + "' has no CUDA backend.", false);
}

const std::uint8_t* ownRows(const SolverOptions& o, std::size_t elements)
{
  if (!o.partition)
  {
    return nullptr;
  }
  if (o.partition->rows.size() != elements || !o.partition->sum)
  {
    throw Error("The partition marks " + std::to_string(o.partition->rows.size()) + " rows for " +
      std::to_string(elements) + " elements, or has no exchange; give one flag per element.");
  }
  return o.partition->rows.data();
}

std::size_t ownRowCount(const SolverOptions& o, std::size_t elements)
{
  const std::uint8_t* own = ownRows(o, elements);
  return own ? std::size_t(std::count_if(own, own + elements, [](std::uint8_t r) { return r != 0; })) : elements;
}

std::function<void(std::vector<Vec3f>&)> exchangeOf(const SolverOptions& o)
{
  if (!o.partition)
  {
    return {};
  }
  const std::shared_ptr<const Partition> partition = o.partition;
  return [partition](std::vector<Vec3f>& values) { partition->exchange(values); };
}

Changes changesBetween(const Scene& now, const SolverOptions& o, const Scene& before,
  const SolverOptions& b, Changes knownSame)
{
  Changes c = 0;
  const auto unknown = [knownSame](Changes bit) { return !(knownSame & bit); };
  const auto differs = [&](Changes bit, bool different) {
    if (unknown(bit) && different)
    {
      c |= bit;
    }
  };
  // unknown(bit) && ...: a known array is not compared (nor read: it may be lent away).
  differs(kTopology, unknown(kTopology) &&
    (now.vertexCount() != before.vertexCount() || !sameBits(now.triangles, before.triangles)));
  differs(kPositions, unknown(kPositions) && !sameBits(now.positions, before.positions));
  differs(kNormals, unknown(kNormals) && !sameBits(now.normals, before.normals));
  differs(kLights, !sameBits(now.lights, before.lights));
  // Materials are part of kAlbedo: what a surface does with the light that reaches it.
  differs(kAlbedo, unknown(kAlbedo) &&
    (!sameBits(now.albedo, before.albedo) || !sameBits(now.triangleMaterials, before.triangleMaterials) ||
      !sameBits(now.triangleIor, before.triangleIor)));
  differs(kEmission, unknown(kEmission) && !sameBits(now.emission, before.emission));
  const Environment &en = now.environment, &eb = before.environment;
  differs(kEnvironmentLayout, en.hasTexture() != eb.hasTexture() || en.width != eb.width || en.height != eb.height);
  const bool sameColor = std::memcmp(&en.color, &eb.color, sizeof(Vec3f)) == 0;
  differs(kEnvironmentRadiance, !sameColor || !sameBits(en.texels, eb.texels));
  differs(kSampling, o.raysPerVertex != b.raysPerVertex || o.twist != b.twist || o.seed != b.seed ||
    o.partition != b.partition);
  differs(kSides, o.twoSided != b.twoSided);
  differs(kLightSampling, o.lightOversampling != b.lightOversampling);
  differs(kIteration, o.bounces != b.bounces);
  differs(kFiltering, smoothingOn(o) != smoothingOn(b) || o.featureAngleDegrees != b.featureAngleDegrees);
  differs(kBackendSetup, o.cudaBvhBuild != b.cudaBvhBuild);
  differs(kPlacement, o.backend != b.backend || o.cudaDevices != b.cudaDevices);
  differs(kMethodOptions, methodOptionsDiffer(o, b));
  if (o.method != b.method)
  {
    c = kEverything;
  }
  return c;
}

std::uint32_t staleStages(const std::vector<StageSpec>& stages, Changes changes)
{
  if (stages.size() > 32)
  {
    throw Error("A method may have at most 32 stages; this one has " + std::to_string(stages.size()) + ".");
  }
  std::uint32_t stale = 0;
  for (std::size_t i = 0; i < stages.size(); ++i)
  {
    if ((stages[i].dependsOn & changes) || (stages[i].after & stale))
    {
      stale |= 1u << i;
    }
  }
  return stale;
}

void StageContext::check(double fraction) const
{
  if (progress && !progress(stageName, fraction))
  {
    throw Aborted();
  }
}

void StageContext::part(const char* name, double ms) const
{
  StageStats record;
  record.name = name;
  record.parent = stageName;
  record.ran = true;
  record.ms = ms;
  stats.stages.push_back(std::move(record));
}
}
}
