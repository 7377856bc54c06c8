// Lighting through a decimated proxy: decimate once per geometry, solve the proxy with the
// ordinary Solver, direct light on the input with the shared light-link code, and carry the
// proxy's indirect light to the input.
#include "linkgi/Resolution.h"
#include "resolution/Decimate.h"

#include "engine/Pipeline.h"

#include "shared/Bounce.h"
#include "shared/DirectLight.h"
#include "linkgi/Error.h"
#include "shared/Surface.h"
#include "scene/Topology.h"

#include <atomic>
#include <chrono>
#include <future>

namespace linkgi
{
namespace
{
using engine::msSince;

void addPart(SolverStats& stats, const char* name, double ms)
{
  StageStats part;
  part.name = name;
  part.ran = true;
  part.ms = ms;
  stats.stages.push_back(std::move(part));
}
}

struct ProxySolver::Impl
{
  Solver inner;
  // Per input geometry and target: the validated input's geometry, the proxy, the transfer
  // and what shadow rays on the input need.
  bool haveGeometry = false;
  std::vector<Vec3f> positions, normals;
  std::vector<Triangle> triangles;
  std::size_t target = 0;
  ProxyMesh proxy;
  ProxyTransfer transfer;
  Topology topology;
  std::vector<RayOrigin> origins;
  std::unique_ptr<RayTracer> tracer;
  std::uint64_t decimations = 0;

  Solution solution;
  SolverStats stats;
};

ProxySolver::ProxySolver() : impl(std::make_unique<Impl>()) {}
ProxySolver::~ProxySolver() = default;

const Solution& ProxySolver::solution() const
{
  return impl->solution;
}

const SolverStats& ProxySolver::stats() const
{
  return impl->stats;
}

const ProxyMesh& ProxySolver::proxy() const
{
  return impl->proxy;
}

std::uint64_t ProxySolver::decimations() const
{
  return impl->decimations;
}

const Solution& ProxySolver::update(const Scene& input, const SolverOptions& options,
  std::size_t proxyVertices, const ProgressCallback& progress)
{
  validateOptions(options);
  Impl& m = *impl;
  Scene s = input;
  std::vector<std::string> warnings = validateScene(s, options.albedoPolicy);
  std::vector<std::pair<const char*, double>> parts;
  const bool sameGeometry = m.haveGeometry && m.target == proxyVertices && sameBits(s.positions, m.positions) &&
    sameBits(s.normals, m.normals) && sameBits(s.triangles, m.triangles);
  // Everything per geometry is made aside and kept only once the whole update succeeded.
  Impl fresh;
  Impl& g = sameGeometry ? m : fresh;
  DirectLightResult direct;
  std::atomic<bool> stop{ false }; // the decimation failed: the other thread's work is moot
  const auto directLight = [&] {
    const auto t = std::chrono::steady_clock::now();
    direct = computeDirectLight(s, g.topology, g.origins, *g.tracer, options.twoSided, options.lightOversampling,
      [&stop](const char*, double) { return !stop; });
    return msSince(t);
  };
  double directMs = 0.0;
  if (!sameGeometry)
  {
    auto t = std::chrono::steady_clock::now();
    // OpenMesh decimates on this thread, the input's shadow-ray structures and its direct
    // light are made on another meanwhile. The future waits for them on every way out.
    std::future<void> inputSide = std::async(std::launch::async, [&] {
      g.topology = Topology::build(s.vertexCount(), s.triangles);
      g.origins = rayOrigins(s, g.topology);
      g.tracer = createCpuRayTracer();
      g.tracer->build(s.positions, s.triangles);
      directMs = directLight();
    });
    try
    {
      g.proxy = decimate(s, proxyVertices, 60.f, progress); // checks the target
    }
    catch (...)
    {
      stop = true;
      throw;
    }
    parts.emplace_back("Decimate", msSince(t));
    t = std::chrono::steady_clock::now();
    g.transfer = buildTransfer(s, g.proxy.scene);
    inputSide.get(); // rethrows what the other thread threw
    parts.emplace_back("Transfer", msSince(t));
  }
  else
  {
    directMs = directLight();
  }
  // On a new geometry, made during the decimation.
  parts.emplace_back("InputDirect", directMs);
  // The proxy's materials and lights follow the input's on every update.
  Scene& p = g.proxy.scene;
  for (std::size_t v = 0; v < g.proxy.sourceVertex.size(); ++v)
  {
    p.albedo[v] = s.albedo[g.proxy.sourceVertex[v]];
  }
  p.emission.clear();
  for (std::size_t v = 0; !s.emission.empty() && v < g.proxy.sourceVertex.size(); ++v)
  {
    p.emission.push_back(s.emission[g.proxy.sourceVertex[v]]);
  }
  p.lights = s.lights;
  p.environment = s.environment;

  const Solution& onProxy = m.inner.update(p, options, progress);

  // Element layout: front sides, then back sides (two-sided), on both meshes.
  const Elements elements{ s.vertexCount(), options.twoSided };
  const std::size_t nv = s.vertexCount(), np = p.vertexCount();
  Solution sol;
  sol.direct = direct.irradiance;
  sol.indirect.resize(elements.count());
  sol.radiance.resize(elements.count());
  for (std::size_t side = 0; side < (options.twoSided ? 2u : 1u); ++side)
  {
    const std::vector<Vec3f> values(onProxy.indirect.begin() + side * np, onProxy.indirect.begin() + (side + 1) * np);
    const std::vector<Vec3f> carried = g.transfer.apply(values);
    std::copy(carried.begin(), carried.end(), sol.indirect.begin() + side * nv);
  }
  for (std::size_t e = 0; e < elements.count(); ++e)
  {
    const Vec3f le = (e < nv && !s.emission.empty()) ? s.emission[e] : Vec3f(0.f);
    sol.radiance[e] = outgoingRadiance(s.albedo[elements.vertexOf(e)], sol.direct[e], sol.indirect[e], le);
  }

  // Commit.
  if (!sameGeometry)
  {
    m.proxy = std::move(fresh.proxy);
    m.transfer = std::move(fresh.transfer);
    m.topology = std::move(fresh.topology);
    m.origins = std::move(fresh.origins);
    m.tracer = std::move(fresh.tracer);
    ++m.decimations;
    m.positions = std::move(s.positions);
    m.normals = std::move(s.normals);
    m.triangles = std::move(s.triangles);
    m.target = proxyVertices;
    m.haveGeometry = true;
  }
  m.solution = std::move(sol);
  m.stats = m.inner.stats();
  m.stats.warnings.insert(m.stats.warnings.begin(), warnings.begin(), warnings.end());
  if (m.proxy.scene.vertexCount() > proxyVertices + proxyVertices / 10)
  {
    m.stats.warnings.push_back("The proxy has " + std::to_string(m.proxy.scene.vertexCount()) +
      " vertices, more than the " + std::to_string(proxyVertices) +
      " asked for: fewer would have turned its faces too far from the surface's normals.");
  }
  if (m.proxy.droppedTriangles > 0)
  {
    m.stats.warnings.push_back("The proxy left out " + std::to_string(m.proxy.droppedTriangles) +
      " non-manifold input triangles; their vertices take the light of the nearest proxy triangle.");
  }
  for (const auto& part : parts)
  {
    addPart(m.stats, part.first, part.second);
  }
  return m.solution;
}
}
