// Adaptive refinement: where to split (edgesToRefine), how (splitEdges: conforming 1-to-2,
// 1-to-3 and 1-to-4 splits of the indexed triangles), and the solve-split-solve loop.
// The split works on the triangle list itself rather than on a halfedge structure: it needs
// no manifold input (OpenMesh drops non-manifold faces on import), and a midpoint split is
// conforming with an edge map alone.
#include "linkgi/Resolution.h"
#include "resolution/Refinement.h"

#include "engine/Pipeline.h"

#include "linkgi/Error.h"
#include "cpu/Parallel.h"
#include "shared/RayOrigin.h"
#include "shared/Metrics.h"
#include "shared/DirectLight.h"
#include "scene/Topology.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace linkgi
{
namespace
{
std::uint64_t edgeKey(Index a, Index b)
{
  return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
}

float distance2(const Vec3f& a, const Vec3f& b)
{
  const Vec3f d = a - b;
  return dot(d, d);
}
}

void validateRefinementOptions(const RefinementOptions& o, std::size_t inputVertices)
{
  if (!(o.tolerance > 0.f && o.tolerance <= 10.f))
  {
    throw Error("Refinement tolerance must be in (0, 10] (a relative change of the light "
                "across an edge); it is " + std::to_string(o.tolerance) + ".");
  }
  if (o.rounds < 1 || o.rounds > 10)
  {
    throw Error("Refinement rounds must be 1 to 10; it is " + std::to_string(o.rounds) + ".");
  }
  if (o.maxVertices != 0 && o.maxVertices < inputVertices)
  {
    throw Error("The refinement vertex budget (" + std::to_string(o.maxVertices) +
      ") is below the input's " + std::to_string(inputVertices) +
      " vertices; refinement only adds vertices (0 = 4 times the input).");
  }
}

void splitEdges(RefinedScene& r, const std::vector<std::pair<Index, Index>>& edges)
{
  Scene& s = r.scene;
  const bool emissive = !s.emission.empty();
  std::unordered_map<std::uint64_t, Index> midpoint;
  midpoint.reserve(edges.size() * 2);
  for (const auto& [a, b] : edges)
  {
    if (a == b || a >= s.vertexCount() || b >= s.vertexCount())
    {
      throw Error("splitEdges: edge (" + std::to_string(a) + ", " + std::to_string(b) +
        ") is not an edge of the mesh.");
    }
    const auto inserted = midpoint.emplace(edgeKey(a, b), Index(s.vertexCount()));
    if (!inserted.second)
    {
      continue; // listed twice
    }
    if (s.vertexCount() >= std::size_t(kInvalidIndex))
    {
      throw Error("Refinement would exceed the engine's 2^32 - 1 vertices.");
    }
    s.positions.push_back((s.positions[a] + s.positions[b]) * 0.5f);
    Vec3f n = normalize(s.normals[a] + s.normals[b]);
    s.normals.push_back(dot(n, n) > 0.f ? n : s.normals[a]);
    s.albedo.push_back((s.albedo[a] + s.albedo[b]) * 0.5f);
    if (emissive)
    {
      s.emission.push_back((s.emission[a] + s.emission[b]) * 0.5f);
    }
    r.midpointOf.push_back({ std::min(a, b), std::max(a, b) });
  }

  std::vector<Triangle> triangles;
  std::vector<Index> sources;
  triangles.reserve(s.triangles.size() + 3 * midpoint.size());
  sources.reserve(triangles.capacity());
  const auto emit = [&](Index a, Index b, Index c, Index source)
  {
    triangles.push_back({ { a, b, c } });
    sources.push_back(source);
  };
  std::size_t split = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
  {
    const Index* v = s.triangles[t].v;
    const Index source = r.sourceTriangle[t];
    Index m[3];
    int count = 0;
    for (int i = 0; i < 3; ++i)
    {
      const auto it = midpoint.find(edgeKey(v[i], v[(i + 1) % 3]));
      m[i] = it == midpoint.end() ? kInvalidIndex : it->second;
      count += m[i] != kInvalidIndex;
    }
    if (count == 0)
    {
      emit(v[0], v[1], v[2], source);
      continue;
    }
    ++split;
    if (count == 1)
    {
      const int i = m[0] != kInvalidIndex ? 0 : m[1] != kInvalidIndex ? 1 : 2;
      const Index a = v[i], b = v[(i + 1) % 3], c = v[(i + 2) % 3];
      emit(a, m[i], c, source);
      emit(m[i], b, c, source);
    }
    else if (count == 2)
    {
      // The edge (c, a) stays whole; (a, b) and (b, c) are split at mab and mbc.
      const int i = m[0] == kInvalidIndex ? 0 : m[1] == kInvalidIndex ? 1 : 2;
      const Index a = v[(i + 1) % 3], b = v[(i + 2) % 3], c = v[i];
      const Index mab = m[(i + 1) % 3], mbc = m[(i + 2) % 3];
      emit(mab, b, mbc, source);
      const std::vector<Vec3f>& p = s.positions;
      if (distance2(p[a], p[mbc]) <= distance2(p[mab], p[c]))
      {
        emit(a, mab, mbc, source);
        emit(a, mbc, c, source);
      }
      else
      {
        emit(a, mab, c, source);
        emit(mab, mbc, c, source);
      }
    }
    else
    {
      emit(v[0], m[0], m[2], source);
      emit(m[0], v[1], m[1], source);
      emit(m[2], m[1], v[2], source);
      emit(m[0], m[1], m[2], source);
    }
  }
  if (split == 0 && !midpoint.empty())
  {
    throw Error("splitEdges: none of the edges to split is an edge of a triangle.");
  }
  s.triangles = std::move(triangles);
  r.sourceTriangle = std::move(sources);
}

std::vector<std::pair<Index, Index>> edgesToRefine(const Scene& s, const Solution& solution,
  const RayTracer& tracer, float tolerance, const ProgressCallback& progress)
{
  const std::size_t n = s.vertexCount();
  const std::size_t elements = solution.elementCount();
  if (elements != n && elements != 2 * n)
  {
    throw Error("edgesToRefine: the solution has " + std::to_string(elements) +
      " elements, the scene " + std::to_string(n) + " vertices.");
  }
  const int sides = elements == 2 * n ? 2 : 1;
  const Topology topology = Topology::build(n, s.triangles);
  const std::vector<RayOrigin> origins = rayOrigins(s, topology);
  const std::vector<float> areas = vertexAreas(s);
  // The level below which differences do not count: 2% of the scene's mean light, so
  // that the noise of a dark corner does not refine it.
  double weighted = 0.0, area = 0.0;
  for (std::size_t i = 0; i < elements; ++i)
  {
    const double a = areas[i % n];
    weighted += a * luminance(solution.direct[i] + solution.indirect[i]);
    area += a;
  }
  const float floorLevel = area > 0.0 ? float(0.02 * weighted / area) : 0.f;
  const float minLength = boundingDiagonal(s.positions) * (1.f / 4096.f);
  const float minLength2 = minLength * minLength;

  const auto& edges = topology.edges;
  std::vector<float> score(edges.size(), 0.f);
  parallelFor("Refine", edges.size(), 64,
    [&](std::size_t begin, std::size_t end)
    {
      for (std::size_t e = begin; e < end; ++e)
      {
        const Index a = edges[e].first, b = edges[e].second;
        if (distance2(s.positions[a], s.positions[b]) < minLength2)
        {
          continue;
        }
        float worst = 0.f;
        for (int side = 0; side < sides; ++side)
        {
          const std::size_t ea = a + side * n, eb = b + side * n;
          const float da = luminance(solution.direct[ea]), db = luminance(solution.direct[eb]);
          const float ia = luminance(solution.indirect[ea]), ib = luminance(solution.indirect[eb]);
          const float level = std::max(0.5f * (da + ia + db + ib), floorLevel);
          if (!(level > 0.f))
          {
            continue;
          }
          worst = std::max({ worst, std::abs(da - db) / level, std::abs(ia - ib) / level });
          if (s.lights.empty())
          {
            continue;
          }
          const float sign = side == 0 ? 1.f : -1.f;
          Vec3f normal = normalize(s.normals[a] + s.normals[b]);
          if (!(dot(normal, normal) > 0.f))
          {
            normal = s.normals[a];
          }
          const Vec3f mid = (s.positions[a] + s.positions[b]) * 0.5f;
          const float dm = luminance(directIrradiance(
            s, mid, normal * sign, tracer, std::min(origins[a].offset, origins[b].offset),
            (origins[a].shift + origins[b].shift) * 0.5f));
          worst = std::max(worst, std::abs(dm - 0.5f * (da + db)) / level);
        }
        score[e] = worst;
      }
    },
    progress);

  std::vector<std::size_t> order;
  for (std::size_t e = 0; e < edges.size(); ++e)
  {
    if (score[e] > tolerance)
    {
      order.push_back(e);
    }
  }
  std::stable_sort(order.begin(), order.end(),
    [&](std::size_t x, std::size_t y) { return score[x] > score[y]; });
  std::vector<std::pair<Index, Index>> out;
  out.reserve(order.size());
  for (std::size_t e : order)
  {
    out.push_back(edges[e]);
  }
  return out;
}

struct RefiningSolver::Impl
{
  Solver solver;
  RefinedScene refined;
  Solution solution;
  SolverStats stats;
  std::vector<std::uint64_t> splits;
  /// What the refined surface was made from: the input's geometry and materials, and the
  /// options. While they stay, an update keeps the surface and solves only its light.
  Scene madeFrom;
  SolverOptions options;
  RefinementOptions refinement;
  bool valid = false;

  bool sameSurface(const Scene& s, const SolverOptions& o, const RefinementOptions& r) const
  {
    return valid && o == options && r.tolerance == refinement.tolerance &&
      r.maxVertices == refinement.maxVertices && r.rounds == refinement.rounds &&
      s.positions == madeFrom.positions && s.normals == madeFrom.normals &&
      std::equal(s.triangles.begin(), s.triangles.end(), madeFrom.triangles.begin(), madeFrom.triangles.end(),
        [](const Triangle& a, const Triangle& b) { return std::equal(a.v, a.v + 3, b.v); }) &&
      s.triangleMaterials == madeFrom.triangleMaterials && s.triangleIor == madeFrom.triangleIor;
  }
};

namespace
{
/// The input's lights, environment, albedo and emission on its refined copy: midpoints take
/// the mean of their two parents, as splitEdges gave them.
void carryShading(const Scene& input, RefinedScene& refined)
{
  Scene& s = refined.scene;
  s.lights = input.lights;
  s.environment = input.environment;
  s.albedo.assign(input.albedo.begin(), input.albedo.end());
  s.emission.assign(input.emission.begin(), input.emission.end());
  for (const std::array<Index, 2>& m : refined.midpointOf)
  {
    s.albedo.push_back((s.albedo[m[0]] + s.albedo[m[1]]) * 0.5f);
    if (!s.emission.empty())
    {
      s.emission.push_back((s.emission[m[0]] + s.emission[m[1]]) * 0.5f);
    }
  }
}
}

RefiningSolver::RefiningSolver() : impl(std::make_unique<Impl>()) {}
RefiningSolver::~RefiningSolver() = default;

const RefinedScene& RefiningSolver::refined() const
{
  return impl->refined;
}
const Solution& RefiningSolver::solution() const
{
  return impl->solution;
}
const SolverStats& RefiningSolver::stats() const
{
  return impl->stats;
}
const std::vector<std::uint64_t>& RefiningSolver::splitsPerRound() const
{
  return impl->splits;
}

const Solution& RefiningSolver::update(const Scene& scene, const SolverOptions& options,
  const RefinementOptions& refinement, const ProgressCallback& progress)
{
  const auto start = std::chrono::steady_clock::now();
  validateRefinementOptions(refinement, scene.vertexCount());
  validateOptions(options);
  if (impl->sameSurface(scene, options, refinement))
  {
    // Lights, albedo, emission or the environment changed: the surface refined for the
    // last geometry stays, and the solver reuses what it keeps for it (a light move costs
    // shadow rays and bounces, as without refinement).
    RefinedScene next = impl->refined;
    carryShading(scene, next);
    impl->solver.update(next.scene, options, progress);
    impl->refined = std::move(next);
    impl->solution = impl->solver.solution();
    const std::vector<std::string> warnings = std::move(impl->stats.warnings);
    impl->stats = impl->solver.stats();
    impl->stats.stages.push_back({ "Refine", "", "", false, 0.0, 0 });
    impl->stats.warnings = warnings;
    impl->stats.msTotal = engine::msSince(start);
    return impl->solution;
  }
  // Validation may drop degenerate triangles (keeping the order of the others): refine
  // what it keeps, and remember which input triangle each one is.
  Scene checked = scene;
  const std::vector<std::string> warnings = validateScene(checked, options.albedoPolicy);
  RefinedScene current;
  current.scene = scene;
  current.scene.triangles = checked.triangles;
  current.inputVertices = scene.vertexCount();
  for (std::size_t t = 0, j = 0; t < checked.triangles.size(); ++t, ++j)
  {
    const auto same = [&](std::size_t k)
    { return std::equal(scene.triangles[k].v, scene.triangles[k].v + 3, checked.triangles[t].v); };
    while (j < scene.triangles.size() && !same(j))
    {
      ++j;
    }
    if (j == scene.triangles.size())
    {
      throw Error("Refinement: scene validation reordered the triangles.");
    }
    current.sourceTriangle.push_back(Index(j));
  }
  const std::size_t budget =
    refinement.maxVertices != 0 ? refinement.maxVertices : 4 * scene.vertexCount();

  // Progress: the first solve and each round (find + split + solve) get equal shares.
  const double shares = 1.0 + refinement.rounds;
  std::size_t step = 0;
  const auto stepProgress = [&](const char* stage, double fraction)
  { return !progress || progress(stage, (double(step) + fraction) / shares); };
  Solver& solver = impl->solver;
  solver.update(current.scene, options, stepProgress);
  std::vector<std::uint64_t> splits;
  double msRefine = 0.0;
  std::unique_ptr<RayTracer> tracer = createCpuRayTracer();
  for (std::uint32_t round = 0; round < refinement.rounds; ++round)
  {
    ++step;
    const std::size_t room = budget > current.scene.vertexCount() ? budget - current.scene.vertexCount() : 0;
    if (room == 0)
    {
      break;
    }
    const auto refineStart = std::chrono::steady_clock::now();
    tracer->build(current.scene.positions, current.scene.triangles);
    std::vector<std::pair<Index, Index>> edges = edgesToRefine(
      current.scene, solver.solution(), *tracer, refinement.tolerance,
      [&](const char* stage, double f) { return stepProgress(stage, 0.1 * f); });
    if (edges.empty())
    {
      break;
    }
    if (edges.size() > room)
    {
      edges.resize(room); // the worst first
    }
    splitEdges(current, edges);
    msRefine += engine::msSince(refineStart);
    splits.push_back(edges.size());
    solver.update(current.scene, options,
      [&](const char* stage, double f) { return stepProgress(stage, 0.1 + 0.9 * f); });
  }
  if (progress && !progress("Refine", 1.0))
  {
    throw Aborted();
  }
  // Commit: nothing above changed the previous result.
  impl->refined = std::move(current);
  impl->solution = solver.solution();
  impl->stats = solver.stats();
  impl->stats.stages.push_back({ "Refine", "", "", msRefine > 0.0, msRefine, 0 });
  for (const std::string& w : warnings)
  {
    if (std::find(impl->stats.warnings.begin(), impl->stats.warnings.end(), w) == impl->stats.warnings.end())
    {
      impl->stats.warnings.push_back(w);
    }
  }
  impl->stats.msTotal = engine::msSince(start);
  impl->splits = std::move(splits);
  impl->madeFrom = scene;
  impl->options = options;
  impl->refinement = refinement;
  impl->valid = true;
  return impl->solution;
}
}
