#include "pm/PhotonMapping.h"

#include "ir/IrBackends.h"

#include "linkgi/Links.h"
#include "linkgi/Metrics.h"
#include "linkgi/Reference.h"
#include "linkgi/Sampling.h"

#include <algorithm>
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
/// Photons count towards a site's estimate within 37 degrees of its normal.
constexpr float kEstimateCos = 0.8f;

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

Vec3f unitOr(const Vec3f& v, const Vec3f& fallback)
{
  const float l2 = dot(v, v);
  return l2 > 0.f ? v * (1.f / std::sqrt(l2)) : fallback;
}
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

Vec3f PhotonMap::radiance(const Vec3f& y, const Vec3f& n, std::vector<std::pair<float, Index>>& scratch) const
{
  (void)scratch;
  return lookupRadiance({ sites.view(), siteNormals.data(), siteRadiance.data() }, y, n);
}

void tracePhotons(const Scene& scene, const std::vector<Vec3f>& faceNormals, const RayTracer& tracer,
  const SolverOptions& options, PhotonMap& map, const ProgressCallback& progress)
{
  SolverOptions paths = options;
  paths.instantRadiosity.vplCount = options.photonMapping.photons;
  paths.instantRadiosity.russianRoulette = true;
  ir::PathSetup setup = ir::buildPathSetup(scene, faceNormals, paths);
  if (scene.hasSpecular())
  {
    setup.view.materials = reinterpret_cast<const std::uint8_t*>(scene.triangleMaterials.data());
    setup.view.ior = scene.triangleIor.empty() ? nullptr : scene.triangleIor.data();
  }
  const ir::VplSet hits = ir::traceVplsCpu(setup, tracer, 1, progress);
  for (auto* a : { &map.positions, &map.normals, &map.flux, &map.causticPositions, &map.causticNormals, &map.causticFlux })
  {
    a->clear();
  }
  for (const ir::Vpl& vpl : hits.vpls)
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
}

std::vector<Vec3f> causticReference(const Scene& s, const std::vector<Vec3f>& faceNormals,
  const RayTracer& tracer, std::uint32_t paths, std::uint32_t seed, const ProgressCallback& progress)
{
  SolverOptions o;
  o.bounces = 1; // to the first diffuse hit
  o.seed = seed;
  o.instantRadiosity.vplCount = paths;
  ir::PathSetup setup = ir::buildPathSetup(s, faceNormals, o);
  const std::size_t nv = s.vertexCount();
  std::vector<Vec3f> out(nv, Vec3f(0.f));
  if (!s.hasSpecular() || setup.view.paths == 0)
  {
    return out;
  }
  setup.view.materials = reinterpret_cast<const std::uint8_t*>(s.triangleMaterials.data());
  setup.view.ior = s.triangleIor.empty() ? nullptr : s.triangleIor.data();
  const std::vector<float> area = vertexAreas(s);
  std::mutex merge;
  std::vector<double> total(3 * nv, 0.0);
  parallelFor("Caustics", setup.view.paths, 16384, [&](std::size_t begin, std::size_t end) {
    std::vector<double> local(3 * nv, 0.0);
    ir::Vpl slots[2];
    for (std::size_t p = begin; p < end; ++p)
    {
      Hit last;
      const int count = ir::traceLightPath(setup.view, std::uint32_t(p), slots, [&](const Ray& ray) {
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
  const ProgressCallback& progress)
{
  std::vector<Vec3f> out(s.vertexCount(), Vec3f(0.f));
  if (map.causticPositions.empty())
  {
    return out;
  }
  const PointTree caustics(map.causticPositions);
  const std::vector<float> area = vertexAreas(s);
  const float max2 = maxRadius * maxRadius;
  parallelFor("Gather", s.vertexCount(), 256, [&](std::size_t begin, std::size_t end) {
    std::vector<std::pair<float, Index>> found;
    for (std::size_t v = begin; v < end; ++v)
    {
      const Vec3f n = s.normals[v];
      const auto sameSide = [&](Index j) { return dot(map.causticNormals[j], n) > kEstimateCos; };
      if (caustics.nearest(s.positions[v], k, max2, sameSide, found) == 0)
      {
        continue;
      }
      // A cone filter of radius R: the k-th photon's distance, but at least the radius of a
      // disc as large as the vertex's one-ring (3 x its area), where its weight (1 - d/R)
      // integrates like the vertex's hat function. A caustic sharper than the mesh then keeps
      // its power instead of the one vertex that holds it claiming a tiny disc's density.
      float r2 = found.size() == k ? found.back().first : max2;
      const float ring2 = 3.f * area[v] / kPi;
      if (ring2 > r2)
      {
        r2 = ring2;
        caustics.nearest(s.positions[v], std::numeric_limits<std::uint32_t>::max(), r2, sameSide, found);
      }
      const float radius = std::sqrt(r2);
      Vec3f sum(0.f);
      for (const auto& f : found)
      {
        sum += map.causticFlux[f.second] * std::max(0.f, 1.f - std::sqrt(f.first) / radius);
      }
      const Vec3f& rho = s.albedo[v];
      for (int c = 0; c < 3; ++c)
      {
        out[v][c] = rho[c] > 0.f && r2 > 0.f ? sum[c] * 3.f / (kPi * r2 * rho[c]) : 0.f;
      }
    }
  }, progress);
  return out;
}

void estimateRadiance(PhotonMap& map, std::uint32_t k, std::uint32_t siteStride, const ProgressCallback& progress)
{
  const std::size_t n = map.count(), stride = std::max<std::uint32_t>(siteStride, 1);
  const std::size_t siteCount = (n + stride - 1) / stride;
  map.sitePositions.resize(siteCount);
  map.siteNormals.resize(siteCount);
  map.siteRadiance.assign(siteCount, Vec3f(0.f));
  const PointTree photons(map.positions);
  parallelFor("Photons", siteCount, 256, [&](std::size_t begin, std::size_t end) {
    std::vector<std::pair<float, Index>> found;
    for (std::size_t s = begin; s < end; ++s)
    {
      const std::size_t i = s * stride;
      const Vec3f& normal = map.normals[i];
      map.sitePositions[s] = map.positions[i];
      map.siteNormals[s] = normal;
      const auto sameSide = [&](Index j) { return dot(map.normals[j], normal) > kEstimateCos; };
      if (photons.nearest(map.positions[i], k, kInfinity, sameSide, found) < 2)
      {
        continue; // a lone photon says nothing about density
      }
      Vec3f sum(0.f);
      for (const auto& f : found)
      {
        sum += map.flux[f.second];
      }
      const float r2 = found.back().first;
      if (r2 > 0.f)
      {
        map.siteRadiance[s] = sum * (1.f / (kPi * kPi * r2));
      }
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
      std::vector<std::pair<float, Index>> found;
      for (std::size_t v = begin; v < end; ++v)
      {
        tree.nearest(s.positions[v], 8, kInfinity, [](Index) { return true; }, found);
        float best = kInfinity;
        for (const auto& f : found)
        {
          const float e = clusterMetric(s.positions[v], s.normals[v], centre[f.second], centreNormal[f.second], a);
          if (e < best)
          {
            best = e;
            out.assignment[v] = f.second;
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
    std::vector<std::pair<float, Index>> found;
    for (std::size_t v = begin; v < end; ++v)
    {
      Index* row = &out.neighbours[v * m];
      row[0] = out.assignment[v];
      int count = 1;
      const auto facing = [&](Index j) { return j != row[0] && dot(s.normals[out.sample[j]], s.normals[v]) > 0.f; };
      samples.nearest(s.positions[v], m - 1, kInfinity, facing, found);
      for (const auto& f : found)
      {
        row[count++] = f.second;
      }
    }
  });
  return out;
}

/// Gather rays that hit a mirror or glass go on (reflected, or refracted with the Fresnel
/// odds), until they hit a diffuse surface, leave, or take kMaxSpecularBounces turns.
void followSpecular(const Scene& s, const std::vector<Vec3f>& faceNormals, const RayTracer& tracer,
  float eps, Index sample, std::vector<Ray>& rays, std::vector<Hit>& hits)
{
  for (std::size_t r = 0; r < rays.size(); ++r)
  {
    for (std::uint32_t turn = 1; turn <= ir::kMaxSpecularBounces; ++turn)
    {
      const Hit& h = hits[r];
      if (h.triangle == kInvalidIndex || s.material(h.triangle) == MaterialType::Diffuse)
      {
        break;
      }
      const Vec3f fn = faceNormals[h.triangle];
      const Triangle& t = s.triangles[h.triangle];
      const float b0 = 1.f - h.u - h.v;
      const Vec3f p = s.positions[t.v[0]] * b0 + s.positions[t.v[1]] * h.u + s.positions[t.v[2]] * h.v;
      Vec3f n = normalize(s.normals[t.v[0]] * b0 + s.normals[t.v[1]] * h.u + s.normals[t.v[2]] * h.v);
      if (!(dot(n, n) > 0.f) || dot(n, fn) <= 0.f)
      {
        n = fn;
      }
      const Vec3f d = normalize(rays[r].direction);
      const bool back = dot(d, fn) > 0.f;
      const Vec3f facing = back ? -n : n;
      const Vec3f next = s.material(h.triangle) == MaterialType::Mirror
        ? ir::reflect(d, facing)
        : ir::dielectricDirection(d, facing, back ? s.ior(h.triangle) : 1.f / s.ior(h.triangle),
            hashToUnit(hash32(sample) ^ std::uint32_t(r), turn));
      rays[r].origin = p + (dot(next, fn) > 0.f ? fn : -fn) * eps;
      rays[r].direction = next;
      rays[r].tnear = 0.f;
      rays[r].tfar = 3.0e38f;
      tracer.trace(&rays[r], &hits[r], 1);
    }
  }
}

SampleIrradiance finalGather(const Scene& s, const std::vector<Vec3f>& shifts,
  const std::vector<Vec3f>& faceNormals, const RayTracer& tracer, const PhotonMap& map,
  const Clusters& clusters, const std::vector<Vec3f>& directions, std::uint32_t seed, float side,
  bool twoSided, const ProgressCallback& progress)
{
  const std::size_t nc = clusters.count(), n = directions.size();
  const float eps = rayEpsilon(s);
  const float diagonal = boundingDiagonal(s.positions);
  // One O(triangles) scan, not one per sample.
  const bool specular = s.hasSpecular();
  SampleIrradiance out;
  out.irradiance.assign(nc, Vec3f(0.f));
  out.harmonicDistance.assign(nc, diagonal);
  parallelFor("Gather", nc, 4, [&](std::size_t begin, std::size_t end) {
    std::vector<Ray> rays(n);
    std::vector<Hit> hits(n);
    std::vector<std::pair<float, Index>> scratch;
    for (std::size_t j = begin; j < end; ++j)
    {
      const Index v = clusters.sample[j];
      const Vec3f normal = s.normals[v] * side;
      const Frame frame = vertexFrame(normal, true, seed, side > 0.f ? v : Index(v + s.vertexCount()));
      const Vec3f origin = elementRayOrigin(s.positions[v], normal, shifts[v], eps);
      for (std::size_t r = 0; r < n; ++r)
      {
        rays[r].origin = origin;
        rays[r].direction = frame.toWorld(directions[r]);
        rays[r].tnear = 0.f;
        rays[r].tfar = 3.0e38f;
      }
      tracer.trace(rays.data(), hits.data(), n);
      if (specular)
      {
        followSpecular(s, faceNormals, tracer, eps, Index(j), rays, hits);
      }
      Vec3f sum(0.f);
      double inverseDistances = 0.0;
      std::size_t hitCount = 0;
      for (std::size_t r = 0; r < n; ++r)
      {
        const Hit& h = hits[r];
        if (h.triangle == kInvalidIndex)
        {
          sum += s.environment.radiance(normalize(rays[r].direction));
          continue;
        }
        Vec3f fn = faceNormals[h.triangle];
        ++hitCount;
        inverseDistances += 1.0 / std::max(double(h.t) * double(length(rays[r].direction)), 1e-30);
        if (dot(rays[r].direction, fn) > 0.f)
        {
          if (!twoSided)
          {
            continue; // the back of a one-sided surface is black
          }
          fn = -fn; // photons arriving at the back were stored with the back's normal
        }
        const Triangle& t = s.triangles[h.triangle];
        const float b0 = 1.f - h.u - h.v;
        const Vec3f y = s.positions[t.v[0]] * b0 + s.positions[t.v[1]] * h.u + s.positions[t.v[2]] * h.v;
        sum += map.radiance(y, fn, scratch);
      }
      out.irradiance[j] = sum * (kPi / float(n));
      if (hitCount > 0)
      {
        out.harmonicDistance[j] = float(double(hitCount) / inverseDistances);
      }
    }
  }, progress);
  out.rays = std::uint64_t(nc) * n;
  return out;
}

std::vector<Vec3f> interpolate(const Scene& s, const Clusters& clusters, const SampleIrradiance& samples)
{
  const std::size_t nv = s.vertexCount();
  constexpr int m = Clusters::kInterpolants;
  std::vector<Vec3f> out(nv);
  parallelRanges(nv, 4096, [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v)
    {
      const Index* row = &clusters.neighbours[v * m];
      Vec3f sum(0.f);
      float weights = 0.f;
      for (int i = 0; i < m && row[i] != kInvalidIndex; ++i)
      {
        const Index j = row[i], sv = clusters.sample[j];
        const float c = dot(s.normals[v], s.normals[sv]);
        if (c <= 0.f)
        {
          continue;
        }
        const float e = length(s.positions[v] - s.positions[sv]) / std::max(samples.harmonicDistance[j], 1e-30f) +
          std::sqrt(std::max(0.f, 2.f - 2.f * c));
        const float w = 1.f / std::max(e, 1e-4f);
        sum += samples.irradiance[j] * w;
        weights += w;
      }
      out[v] = weights > 0.f ? sum / weights : samples.irradiance[row[0]];
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
  return pm::causticReference(scene, frontFaceNormals(scene), *tracer, paths, seed);
}
}
