#include "methods/pm/PhotonMapping.h"

#include "shared/LightPaths.h"

#include "shared/Surface.h"
#include "shared/Metrics.h"
#include "shared/Sampling.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <numeric>
#include <tuple>

#include "linkgi/Error.h"

namespace linkgi::pm
{
namespace
{
constexpr float kInfinity = std::numeric_limits<float>::max();

/// 10 bits per axis of p's place in the box [lo, lo + size], interleaved.
std::uint32_t morton(const Vec3f& p, const Vec3f& lo, float invSize)
{
  const auto spread = [](std::uint32_t x) {
    x = (x | (x << 16)) & 0x030000FFu;
    x = (x | (x << 8)) & 0x0300F00Fu;
    x = (x | (x << 4)) & 0x030C30C3u;
    x = (x | (x << 2)) & 0x09249249u;
    return x;
  };
  std::uint32_t code = 0;
  for (int a = 0; a < 3; ++a)
  {
    const float t = std::min(std::max((p[a] - lo[a]) * invSize, 0.f), 1.f);
    code |= spread(std::uint32_t(t * 1023.f)) << a;
  }
  return code;
}
}

paths::PathSetup pathSetup(const Scene& scene, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const SolverOptions& options)
{
  paths::PathSetup setup = paths::buildPathSetup(scene, faceNormals, origins, options);
  if (scene.hasSpecular())
  {
    setup.view.materials = reinterpret_cast<const std::uint8_t*>(scene.triangleMaterials.data());
    setup.view.ior = scene.triangleIor.empty() ? nullptr : scene.triangleIor.data();
  }
  return setup;
}

Vec3f PhotonMap::totalFlux() const
{
  double sum[3] = { 0.0, 0.0, 0.0 };
  for (const Vec3f& f : flux)
  {
    for (int c = 0; c < 3; ++c)
    {
      sum[c] += f[c];
    }
  }
  return Vec3f(float(sum[0]), float(sum[1]), float(sum[2]));
}

RadianceSitesView PhotonMap::sitesView() const
{
  return { sites.view(), siteNormals.data(), siteRadiance.data(), siteRadius2.data(), maxDistance2 };
}

std::uint64_t tracePhotons(const Scene& scene, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const RayTracer& tracer,
  const SolverOptions& options, PhotonMap& map, const ProgressCallback& progress, std::uint64_t secondPassBytes)
{
  SolverOptions paths = options;
  paths.instantRadiosity.vplCount = options.photonMapping.photons;
  paths.instantRadiosity.russianRoulette = true;
  const paths::PathSetup setup = pathSetup(scene, faceNormals, origins, paths);
  const paths::VplSet hits = paths::traceVplsCpu(setup, tracer, 1, progress, secondPassBytes);
  for (auto* a : { &map.positions, &map.normals, &map.flux, &map.causticPositions, &map.causticNormals, &map.causticFlux })
  {
    a->clear();
  }
  for (const paths::Vpl& vpl : hits.vpls)
  {
    if (vpl.sky)
    {
      continue; // the sky is what a gather ray that leaves the scene sees
    }
    map.positions.push_back(vpl.position);
    map.normals.push_back(vpl.normal);
    map.flux.push_back(vpl.flux);
    if (vpl.caustic)
    {
      map.causticPositions.push_back(vpl.position);
      map.causticNormals.push_back(vpl.normal);
      map.causticFlux.push_back(vpl.flux);
    }
  }
  return hits.secondPassBytes;
}

std::vector<Vec3f> causticReference(const Scene& s, const std::vector<Vec3f>& faceNormals,
  const std::vector<RayOrigin>& origins, const RayTracer& tracer, std::uint32_t paths, std::uint32_t seed, const ProgressCallback& progress)
{
  SolverOptions o;
  o.bounces = 1; // to the first diffuse hit
  o.seed = seed;
  o.instantRadiosity.vplCount = paths;
  const paths::PathSetup setup = pathSetup(s, faceNormals, origins, o);
  const std::size_t nv = s.vertexCount();
  std::vector<Vec3f> out(nv, Vec3f(0.f));
  if (!s.hasSpecular() || setup.view.paths == 0)
  {
    return out;
  }
  const std::vector<float> area = vertexAreas(s);
  std::mutex merge;
  std::vector<double> total(3 * nv, 0.0);
  parallelFor("Caustics", setup.view.paths, 16384, [&](std::size_t begin, std::size_t end) {
    std::vector<double> local(3 * nv, 0.0);
    paths::Vpl slots[2];
    for (std::size_t p = begin; p < end; ++p)
    {
      Hit last;
      const int count = paths::traceLightPath(setup.view, std::uint32_t(p), slots, [&](const Ray& ray) {
        tracer.trace(&ray, &last, 1);
        return last;
      });
      if (count == 0 || !slots[count - 1].caustic)
      {
        continue;
      }
      // The path ended at that hit (one bounce): `last` is it.
      const Triangle& t = s.triangles[last.triangle];
      const float b[3] = { 1.f - last.u - last.v, last.u, last.v };
      const Vec3f rho = s.albedo[t.v[0]] * b[0] + s.albedo[t.v[1]] * b[1] + s.albedo[t.v[2]] * b[2];
      for (int c = 0; c < 3; ++c)
      {
        if (!(rho[c] > 0.f))
        {
          continue;
        }
        const double incident = double(slots[count - 1].flux[c]) / double(rho[c]);
        for (int k = 0; k < 3; ++k)
        {
          local[3 * t.v[k] + c] += incident * b[k] / std::max(double(area[t.v[k]]), 1e-30);
        }
      }
    }
    const std::lock_guard<std::mutex> lock(merge);
    for (std::size_t i = 0; i < local.size(); ++i)
    {
      total[i] += local[i];
    }
  }, progress);
  for (std::size_t v = 0; v < nv; ++v)
  {
    out[v] = Vec3f(float(total[3 * v]), float(total[3 * v + 1]), float(total[3 * v + 2]));
  }
  return out;
}

std::vector<Vec3f> causticIrradiance(const Scene& s, const PhotonMap& map, std::uint32_t k, float maxRadius,
  const ProgressCallback& progress, const std::uint8_t* rows)
{
  std::vector<Vec3f> out(s.vertexCount(), Vec3f(0.f));
  if (map.causticPositions.empty())
  {
    return out;
  }
  const PointTree caustics(map.causticPositions);
  const PhotonsView view{ caustics.view(), map.causticNormals.data(), map.causticFlux.data() };
  const std::vector<float> area = vertexAreas(s);
  parallelFor("Gather", s.vertexCount(), 256, [&](std::size_t begin, std::size_t end) {
    std::vector<Neighbour> heap(k);
    for (std::size_t v = begin; v < end; ++v)
    {
      if (!rows || rows[v])
      {
        out[v] = causticEstimate(view, s.positions[v], s.normals[v], s.albedo[v], area[v], k,
          maxRadius * maxRadius, heap.data());
      }
    }
  }, progress);
  return out;
}

void estimateRadiance(PhotonMap& map, const SurfaceView& surface, std::uint32_t k, std::uint32_t siteStride,
  float maxRadius, const ProgressCallback& progress)
{
  map.maxDistance2 = maxRadius * maxRadius;
  const std::size_t n = map.count(), stride = std::max<std::uint32_t>(siteStride, 1);
  const std::size_t siteCount = (n + stride - 1) / stride;
  map.sitePositions.resize(siteCount);
  map.siteNormals.resize(siteCount);
  map.siteRadiance.resize(siteCount);
  map.siteRadius2.resize(siteCount);
  const PointTree photons(map.positions);
  const PhotonsView view{ photons.view(), map.normals.data(), map.flux.data() };
  parallelFor("Photons", siteCount, 256, [&](std::size_t begin, std::size_t end) {
    std::vector<Neighbour> heap(k);
    for (std::size_t s = begin; s < end; ++s)
    {
      const std::size_t i = s * stride;
      map.sitePositions[s] = map.positions[i];
      map.siteNormals[s] = map.normals[i];
      map.siteRadiance[s] = siteRadiance(view, surface, Index(i), k, map.maxDistance2, heap.data(),
        map.siteRadius2[s]);
    }
  }, progress);
  map.sites = PointTree(map.sitePositions);
}

float clusterMetric(const Vec3f& x, const Vec3f& n, const Vec3f& c, const Vec3f& m, float alphaOverDiagonal)
{
  return alphaOverDiagonal * length(x - c) + std::sqrt(std::max(0.f, 2.f - 2.f * dot(n, m)));
}

Clusters clusterVertices(const Scene& s, std::uint32_t k, float alpha, int iterations, const ProgressCallback& progress)
{
  const std::size_t nv = s.vertexCount();
  const std::size_t kc = std::min<std::size_t>(std::max<std::uint32_t>(k, 1), nv);
  const float diagonal = std::max(boundingDiagonal(s.positions), 1e-30f);
  const float a = alpha / diagonal;

  // Morton order: halves of a range of it are compact regions.
  Vec3f lo = s.positions[0], hi = lo;
  for (const Vec3f& p : s.positions)
  {
    for (int ax = 0; ax < 3; ++ax)
    {
      lo[ax] = std::min(lo[ax], p[ax]);
      hi[ax] = std::max(hi[ax], p[ax]);
    }
  }
  const float size = std::max({ hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-30f });
  std::vector<std::uint32_t> codes(nv);
  for (std::size_t v = 0; v < nv; ++v)
  {
    codes[v] = morton(s.positions[v], lo, 1.f / size);
  }
  std::vector<Index> order(nv);
  std::iota(order.begin(), order.end(), Index(0));
  std::stable_sort(order.begin(), order.end(), [&](Index x, Index y) { return codes[x] < codes[y]; });

  // Adaptive seeding: a range's seeds go to its halves in proportion to their geometric
  // variation (the metric's sum against the half's mean), one seed per range at the end,
  // picked by a hash (the paper's jittered sampling).
  const auto variation = [&](std::size_t b, std::size_t e) {
    Vec3f c(0.f), m(0.f);
    for (std::size_t i = b; i < e; ++i)
    {
      c += s.positions[order[i]];
      m += s.normals[order[i]];
    }
    c = c / float(e - b);
    m = unitOr(m, s.normals[order[b]]);
    double sum = 0.0;
    for (std::size_t i = b; i < e; ++i)
    {
      sum += clusterMetric(s.positions[order[i]], s.normals[order[i]], c, m, a);
    }
    return sum + 1e-12 * double(e - b);
  };
  std::vector<Index> seeds;
  seeds.reserve(kc);
  // Ranges of `order` still to seed: (begin, end, seeds to place in it).
  std::vector<std::tuple<std::size_t, std::size_t, std::size_t>> unseeded{ { 0, nv, kc } };
  while (!unseeded.empty())
  {
    auto [b, e, count] = unseeded.back();
    unseeded.pop_back();
    if (count == 0)
    {
      continue;
    }
    if (count >= e - b)
    {
      for (std::size_t i = b; i < e; ++i)
      {
        seeds.push_back(order[i]);
      }
      continue;
    }
    if (count == 1)
    {
      seeds.push_back(order[b + hash32(Index(b) * 2654435761u + Index(e)) % (e - b)]);
      continue;
    }
    const std::size_t mid = (b + e) / 2;
    const double left = variation(b, mid), right = variation(mid, e);
    std::size_t toLeft = std::size_t(std::llround(double(count) * left / (left + right)));
    toLeft = std::min(std::max(toLeft, count > e - mid ? count - (e - mid) : std::size_t(0)), std::min(count, mid - b));
    unseeded.emplace_back(b, mid, toLeft);
    unseeded.emplace_back(mid, e, count - toLeft);
  }

  // k-means: each vertex joins the best of the 8 centres nearest in space (the paper
  // restricts the search the same way, with a kd-tree of the centres).
  std::vector<Vec3f> centre(seeds.size()), centreNormal(seeds.size());
  for (std::size_t j = 0; j < seeds.size(); ++j)
  {
    centre[j] = s.positions[seeds[j]];
    centreNormal[j] = s.normals[seeds[j]];
  }
  Clusters out;
  out.assignment.assign(nv, 0);
  const auto assign = [&]() {
    const PointTree tree(centre);
    parallelRanges(nv, 1024, [&](std::size_t begin, std::size_t end) {
      std::vector<Neighbour> found;
      for (std::size_t v = begin; v < end; ++v)
      {
        tree.nearest(s.positions[v], 8, kInfinity, [](Index) { return true; }, found);
        float best = kInfinity;
        for (const Neighbour& f : found)
        {
          const float e = clusterMetric(s.positions[v], s.normals[v], centre[f.index], centreNormal[f.index], a);
          if (e < best)
          {
            best = e;
            out.assignment[v] = f.index;
          }
        }
      }
    });
  };
  for (int it = 0; it < iterations; ++it)
  {
    if (progress && !progress("Clusters", double(it) / iterations))
    {
      throw Aborted();
    }
    assign();
    std::vector<Vec3f> sum(centre.size(), Vec3f(0.f)), normalSum(centre.size(), Vec3f(0.f));
    std::vector<std::uint32_t> members(centre.size(), 0);
    for (std::size_t v = 0; v < nv; ++v)
    {
      sum[out.assignment[v]] += s.positions[v];
      normalSum[out.assignment[v]] += s.normals[v];
      ++members[out.assignment[v]];
    }
    for (std::size_t j = 0; j < centre.size(); ++j)
    {
      if (members[j])
      {
        centre[j] = sum[j] / float(members[j]);
        centreNormal[j] = unitOr(normalSum[j], centreNormal[j]);
      }
    }
  }
  assign();

  // Samples: each non-empty cluster's member closest to its centre; clusters renumbered.
  std::vector<float> best(centre.size(), kInfinity);
  std::vector<Index> sampleOf(centre.size(), kInvalidIndex);
  for (std::size_t v = 0; v < nv; ++v)
  {
    const Index j = out.assignment[v];
    const float e = clusterMetric(s.positions[v], s.normals[v], centre[j], centreNormal[j], a);
    if (e < best[j])
    {
      best[j] = e;
      sampleOf[j] = Index(v);
    }
  }
  std::vector<Index> renumber(centre.size(), kInvalidIndex);
  for (std::size_t j = 0; j < centre.size(); ++j)
  {
    if (sampleOf[j] != kInvalidIndex)
    {
      renumber[j] = Index(out.sample.size());
      out.sample.push_back(sampleOf[j]);
    }
  }
  for (Index& j : out.assignment)
  {
    j = renumber[j];
  }

  // Interpolants: the vertex's own cluster, then the clusters of the nearest samples that
  // face the same way.
  std::vector<Vec3f> samplePositions(out.sample.size());
  for (std::size_t j = 0; j < out.sample.size(); ++j)
  {
    samplePositions[j] = s.positions[out.sample[j]];
  }
  const PointTree samples(samplePositions);
  constexpr int m = Clusters::kInterpolants;
  out.neighbours.assign(nv * m, kInvalidIndex);
  parallelRanges(nv, 1024, [&](std::size_t begin, std::size_t end) {
    std::vector<Neighbour> found;
    for (std::size_t v = begin; v < end; ++v)
    {
      Index* row = &out.neighbours[v * m];
      row[0] = out.assignment[v];
      int count = 1;
      const auto facing = [&](Index j) { return j != row[0] && dot(s.normals[out.sample[j]], s.normals[v]) > 0.f; };
      samples.nearest(s.positions[v], m - 1, kInfinity, facing, found);
      for (const Neighbour& f : found)
      {
        row[count++] = f.index;
      }
    }
  });
  // A vertex none of whose interpolants shares its tangent plane (sharesTangentPlane, as
  // interpolateVertex reads them: a plate under a table top, whose cluster's and neighbours'
  // samples lie on the top above it or the floor below) gathers itself, as irradiance caching
  // computes a new record where no cached one is valid.
  for (std::size_t v = 0; v < nv; ++v)
  {
    Index* row = &out.neighbours[v * m];
    bool served = false;
    for (int i = 0; i < m && row[i] != kInvalidIndex && !served; ++i)
    {
      const Index sv = out.sample[row[i]];
      served = dot(s.normals[v], s.normals[sv]) > 0.f &&
        sharesTangentPlane(s.positions[v], s.normals[v], s.positions[sv], s.normals[sv]);
    }
    if (!served)
    {
      out.assignment[v] = row[0] = Index(out.sample.size());
      out.sample.push_back(Index(v));
    }
  }
  return out;
}

SampleIrradiance finalGather(const Scene& s, const std::vector<RayOrigin>& origins,
  const std::vector<Vec3f>& faceNormals, const RayTracer& tracer, const PhotonMap& map,
  const Clusters& clusters, const std::vector<Vec3f>& directions, std::uint32_t seed, float side,
  bool twoSided, const ProgressCallback& progress, const std::uint8_t* rows)
{
  const std::size_t nc = clusters.count(), n = directions.size();
  const paths::PathSetup setup = pathSetup(s, faceNormals, origins, SolverOptions());
  const paths::PathScene& view = setup.view;
  const RadianceSitesView sites = map.sitesView();
  const float diagonal = boundingDiagonal(s.positions);
  SampleIrradiance out;
  out.irradiance.assign(nc, Vec3f(0.f));
  out.harmonicDistance.assign(nc, diagonal);
  std::atomic<std::uint64_t> samplesGathered{ 0 };
  parallelFor("Gather", nc, 4, [&](std::size_t begin, std::size_t end) {
    std::uint64_t gathered = 0;
    std::vector<Ray> rays(n);
    std::vector<Hit> hits(n);
    const ClosestHit trace{ tracer };
    for (std::size_t j = begin; j < end; ++j)
    {
      const Index v = clusters.sample[j];
      if (rows && !rows[v])
      {
        out.harmonicDistance[j] = 0.f; // another process's cluster
        continue;
      }
      ++gathered;
      const Vec3f normal = s.normals[v] * side;
      const Frame frame = vertexFrame(normal, true, seed, side > 0.f ? v : Index(v + s.vertexCount()));
      const Vec3f origin = elementRayOrigin(s.positions[v], normal, origins[v]);
      for (std::size_t r = 0; r < n; ++r)
      {
        rays[r].origin = origin;
        rays[r].direction = frame.toWorld(directions[r]);
        rays[r].tnear = 0.f;
        rays[r].tfar = 3.0e38f;
      }
      tracer.trace(rays.data(), hits.data(), n); // the first hits in one batch
      Vec3f sum(0.f);
      double inverseDistances = 0.0;
      std::size_t hitCount = 0;
      for (std::size_t r = 0; r < n; ++r)
      {
        const GatherHit g = shadeGatherRay(view, sites, rays[r], hits[r], std::uint32_t(j), std::uint32_t(r),
          twoSided, trace);
        sum += g.radiance;
        if (g.hit)
        {
          ++hitCount;
          inverseDistances += 1.0 / std::max(double(g.distance), 1e-30);
        }
      }
      out.irradiance[j] = sum * (kPi / float(n));
      if (hitCount > 0)
      {
        out.harmonicDistance[j] = float(double(hitCount) / inverseDistances);
      }
    }
    samplesGathered += gathered;
  }, progress);
  out.rays = samplesGathered * n;
  return out;
}

std::vector<Vec3f> interpolate(const Scene& s, const Clusters& clusters, const SampleIrradiance& samples)
{
  const std::size_t nv = s.vertexCount();
  std::vector<Vec3f> out(nv);
  parallelRanges(nv, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      out[v] = interpolateVertex(s.positions.data(), s.normals.data(), Index(v),
        &clusters.neighbours[v * kInterpolants], clusters.sample.data(), samples.irradiance.data(),
        samples.harmonicDistance.data());
    }
  });
  return out;
}
}

namespace linkgi
{
std::vector<Vec3f> solveCausticReference(const Scene& input, std::uint32_t paths, std::uint32_t seed)
{
  Scene scene = input;
  validateScene(scene);
  const std::unique_ptr<RayTracer> tracer = createCpuRayTracer();
  tracer->build(scene.positions, scene.triangles);
  const std::vector<RayOrigin> origins = rayOrigins(scene, Topology::build(scene.vertexCount(), scene.triangles));
  return pm::causticReference(scene, frontFaceNormals(scene), origins, *tracer, paths, seed);
}
}
