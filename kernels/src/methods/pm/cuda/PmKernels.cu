#include "methods/pm/cuda/PmKernels.h"

#include "cuda/Primitives.h"

#include "shared/Bvh.h"

#include <cub/device/device_segmented_sort.cuh>

namespace linkgi::pm::gpu
{
namespace
{
constexpr int kThreads = cuda::kBlockThreads;
/// A range's split axis is the longest side of the box of at most this many of its points.
constexpr std::uint32_t kAxisSample = 256;
/// Levels whose ranges hold more points than this on average are sorted by one radix sort of
/// the whole array (a segmented sort gives a large range a single block).
constexpr std::uint32_t kSegmentedSortBelow = 4096;

using cuda::gridBlocks;

__global__ void iotaKernel(Index* order, std::uint32_t n)
{
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n)
  {
    order[i] = i;
  }
}

__global__ void rootKernel(std::uint32_t* begins, std::uint32_t* ends, std::uint32_t n)
{
  begins[0] = 0;
  ends[0] = n;
}

// One warp per range of this level: its split axis (also at its median's place in `axes`),
// and its two halves as the next level's ranges 2s and 2s + 1 (empty where a half is a leaf,
// at the half's start, so that starts never decrease along a level).
__global__ void splitKernel(const Vec3f* points, const Index* order, const std::uint32_t* begins,
  const std::uint32_t* ends, std::uint32_t ranges, std::uint8_t* rangeAxes, std::uint8_t* axes,
  std::uint32_t* nextBegins, std::uint32_t* nextEnds, bool last)
{
  const std::uint32_t s = (blockIdx.x * blockDim.x + threadIdx.x) / 32;
  const int lane = threadIdx.x & 31;
  if (s >= ranges)
  {
    return; // the whole warp: s is the same for its lanes
  }
  const std::uint32_t b = begins[s], e = ends[s];
  if (e - b <= kTreeLeaf)
  {
    if (lane == 0 && !last)
    {
      nextBegins[2 * s] = nextEnds[2 * s] = nextBegins[2 * s + 1] = nextEnds[2 * s + 1] = b;
    }
    return;
  }
  const std::uint32_t size = e - b, stride = size > kAxisSample ? size / kAxisSample : 1u;
  float lo[3] = { 3.4e38f, 3.4e38f, 3.4e38f }, hi[3] = { -3.4e38f, -3.4e38f, -3.4e38f };
  for (std::uint32_t j = lane; j < kAxisSample && std::uint64_t(j) * stride < size; j += 32)
  {
    const Vec3f p = points[order[b + j * stride]];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = fminf(lo[a], p[a]);
      hi[a] = fmaxf(hi[a], p[a]);
    }
  }
  for (int offset = 16; offset > 0; offset /= 2)
  {
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = fminf(lo[a], __shfl_xor_sync(0xffffffffu, lo[a], offset));
      hi[a] = fmaxf(hi[a], __shfl_xor_sync(0xffffffffu, hi[a], offset));
    }
  }
  if (lane != 0)
  {
    return;
  }
  const float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
  const std::uint8_t axis = x >= y && x >= z ? 0 : y >= z ? 1 : 2;
  const std::uint32_t mid = (b + e) / 2;
  rangeAxes[s] = axis;
  axes[mid] = axis;
  if (!last)
  {
    const bool left = mid - b > kTreeLeaf, right = e - mid - 1 > kTreeLeaf;
    nextBegins[2 * s] = b;
    nextEnds[2 * s] = left ? mid : b;
    nextBegins[2 * s + 1] = mid + 1;
    nextEnds[2 * s + 1] = right ? e : mid + 1;
  }
}

/// The range of this level that holds position i, or `ranges` where none does (a median
/// placed earlier, or a leaf).
__device__ std::uint32_t rangeOf(const std::uint32_t* begins, const std::uint32_t* ends, std::uint32_t ranges,
  std::uint32_t i)
{
  // The last range that starts at or before i.
  std::uint32_t lo = 0, hi = ranges;
  while (hi - lo > 1)
  {
    const std::uint32_t m = (lo + hi) / 2;
    if (begins[m] <= i)
    {
      lo = m;
    }
    else
    {
      hi = m;
    }
  }
  return begins[lo] <= i && i < ends[lo] ? lo : ranges;
}

// Segmented sort keys: each position's coordinate along its range's axis (0 outside them:
// the sort does not touch those positions).
__global__ void keysKernel(const Vec3f* points, const Index* order, const std::uint32_t* begins,
  const std::uint32_t* ends, std::uint32_t ranges, const std::uint8_t* rangeAxes, std::uint32_t n, float* keys)
{
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n)
  {
    const std::uint32_t r = rangeOf(begins, ends, ranges, i);
    keys[i] = r < ranges ? points[order[i]][rangeAxes[r]] : 0.f;
  }
}

// Whole-array sort keys that sort every range in place and leave every other position where
// it is: high bits the range's start (the position itself outside the ranges), low bits the
// coordinate's bits in an order that sorts like the floats.
__global__ void globalKeysKernel(const Vec3f* points, const Index* order, const std::uint32_t* begins,
  const std::uint32_t* ends, std::uint32_t ranges, const std::uint8_t* rangeAxes, std::uint32_t n,
  std::uint64_t* keys)
{
  const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n)
  {
    return;
  }
  const std::uint32_t r = rangeOf(begins, ends, ranges, i);
  if (r == ranges)
  {
    keys[i] = std::uint64_t(i) << 32;
    return;
  }
  const std::uint32_t bits = __float_as_uint(points[order[i]][rangeAxes[r]]);
  const std::uint32_t sortable = bits & 0x80000000u ? ~bits : bits | 0x80000000u;
  keys[i] = (std::uint64_t(begins[r]) << 32) | sortable;
}

__global__ void flagKernel(const paths::Vpl* hits, std::size_t count, Index* photon, Index* caustic)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < count)
  {
    photon[i] = hits[i].sky ? 0u : 1u;
    caustic[i] = !hits[i].sky && hits[i].caustic ? 1u : 0u;
  }
}

__global__ void scatterKernel(const paths::Vpl* hits, std::size_t count, const Offset* photonAt,
  const Offset* causticAt, Vec3f* positions, Vec3f* normals, Vec3f* flux, Vec3f* causticPositions,
  Vec3f* causticNormals, Vec3f* causticFlux)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= count || hits[i].sky)
  {
    return;
  }
  const paths::Vpl& h = hits[i];
  const Offset p = photonAt[i];
  positions[p] = h.position;
  normals[p] = h.normal;
  flux[p] = h.flux;
  if (h.caustic)
  {
    const Offset c = causticAt[i];
    causticPositions[c] = h.position;
    causticNormals[c] = h.normal;
    causticFlux[c] = h.flux;
  }
}

// Which tree positions hold a site's photon (every stride-th photon is one).
__global__ void siteFlagKernel(const Index* order, std::uint32_t n, std::uint32_t stride, Index* flags)
{
  const std::uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < n)
  {
    flags[t] = order[t] % stride == 0 ? 1u : 0u;
  }
}

// The tree positions of the sites' photons, in tree order: neighbouring threads then search
// neighbouring photons.
__global__ void siteOrderKernel(const Index* order, std::uint32_t n, std::uint32_t stride, const Offset* at,
  Index* sites)
{
  const std::uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < n && order[t] % stride == 0)
  {
    sites[at[t]] = t;
  }
}

template <int K>
__global__ void sitesKernel(PhotonsView photons, SurfaceView surface, const Index* sitePhotons, std::uint32_t siteCount, std::uint32_t k,
  float max2, Vec3f* sitePositions, Vec3f* siteNormals, Vec3f* siteRadiance, float* siteRadius2)
{
  const std::uint32_t s = blockIdx.x * blockDim.x + threadIdx.x;
  if (s >= siteCount)
  {
    return;
  }
  Neighbour heap[K];
  const Index i = sitePhotons[s];
  sitePositions[s] = photons.tree.points[i];
  siteNormals[s] = photons.normals[i];
  siteRadiance[s] = pm::siteRadiance(photons, surface, i, k, max2, heap, siteRadius2[s]);
}

template <typename T>
__global__ void permuteKernel(const Index* order, std::uint32_t n, const T* in, T* out)
{
  const std::uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < n)
  {
    out[t] = in[order[t]];
  }
}

template <int K>
__global__ void causticKernel(PhotonsView caustics, const Vec3f* positions, const Vec3f* normals,
  const Vec3f* albedo, const float* areas, Index vertexCount, std::uint32_t k, float max2, Vec3f* out)
{
  const Index v = blockIdx.x * blockDim.x + threadIdx.x;
  if (v >= vertexCount)
  {
    return;
  }
  Neighbour heap[K];
  out[v] = causticEstimate(caustics, positions[v], normals[v], albedo[v], areas[v], k, max2, heap);
}

/// Launches kernel<K> for the smallest heap K that holds k.
template <template <int> class Launch, typename... Args>
void withHeap(std::uint32_t k, Args&&... args)
{
  if (k <= 16)
  {
    Launch<16>::run(args...);
  }
  else if (k <= 64)
  {
    Launch<64>::run(args...);
  }
  else if (k <= 256)
  {
    Launch<256>::run(args...);
  }
  else
  {
    Launch<1024>::run(args...);
  }
}

template <int K>
struct SitesLaunch
{
  static void run(const PhotonsView& p, const SurfaceView& surface, const Index* sitePhotons, std::uint32_t siteCount,
    std::uint32_t k,
    float max2, Vec3f* positions, Vec3f* normals, Vec3f* radiance, float* radius2, cudaStream_t stream)
  {
    sitesKernel<K><<<gridBlocks(siteCount), kThreads, 0, stream>>>(p, surface, sitePhotons, siteCount, k, max2, positions,
      normals, radiance, radius2);
    LINKGI_CUDA_CHECK_LAUNCH("sitesKernel");
  }
};

template <int K>
struct CausticLaunch
{
  static void run(const PhotonsView& c, const Vec3f* positions, const Vec3f* normals, const Vec3f* albedo,
    const float* areas, Index vertexCount, std::uint32_t k, float max2, Vec3f* out, cudaStream_t stream)
  {
    causticKernel<K><<<gridBlocks(vertexCount), kThreads, 0, stream>>>(c, positions, normals, albedo, areas,
      vertexCount, k, max2, out);
    LINKGI_CUDA_CHECK_LAUNCH("causticKernel");
  }
};

// One block per cluster: its sample's gather rays, summed in the block.
__global__ void gatherKernel(GatherLaunch g, Vec3f* irradiance, float* harmonicDistance)
{
  const std::uint32_t j = blockIdx.x;
  const Index v = g.samples[j];
  const Vec3f normal = g.scene.normals[v] * g.side;
  const Frame frame = vertexFrame(normal, true, g.seed, g.side > 0.f ? v : Index(v + g.vertexCount));
  const Vec3f origin = elementRayOrigin(g.scene.positions[v], normal, g.scene.origins[v]);
  const auto trace = [&g](const Ray& ray) {
    Hit h;
    bvh::traverse<false>(g.bvh, ray, h);
    return h;
  };
  Vec3f sum(0.f);
  double inverseDistances = 0.0;
  unsigned hits = 0;
  for (std::uint32_t r = threadIdx.x; r < g.directionCount; r += blockDim.x)
  {
    Ray ray;
    ray.origin = origin;
    ray.direction = frame.toWorld(g.directions[r]);
    const GatherHit hit = shadeGatherRay(g.scene, g.sites, ray, trace(ray), j, r, g.twoSided, trace);
    sum += hit.radiance;
    if (hit.hit)
    {
      ++hits;
      inverseDistances += 1.0 / fmax(double(hit.distance), 1e-30);
    }
  }
  __shared__ float sx[kThreads], sy[kThreads], sz[kThreads];
  __shared__ double sd[kThreads];
  __shared__ unsigned sh[kThreads];
  const int t = threadIdx.x;
  sx[t] = sum.x;
  sy[t] = sum.y;
  sz[t] = sum.z;
  sd[t] = inverseDistances;
  sh[t] = hits;
  __syncthreads();
  for (int half = kThreads / 2; half > 0; half /= 2)
  {
    if (t < half)
    {
      sx[t] += sx[t + half];
      sy[t] += sy[t + half];
      sz[t] += sz[t + half];
      sd[t] += sd[t + half];
      sh[t] += sh[t + half];
    }
    __syncthreads();
  }
  if (t == 0)
  {
    irradiance[j] = Vec3f(sx[0], sy[0], sz[0]) * (kPi / float(g.directionCount));
    harmonicDistance[j] = sh[0] > 0 ? float(double(sh[0]) / sd[0]) : g.diagonal;
  }
}

__global__ void interpolateKernel(const Vec3f* positions, const Vec3f* normals, Index vertexCount,
  const Index* neighbours, const Index* samples, const Vec3f* irradiance, const float* harmonicDistance,
  const Vec3f* caustics, cuda::Rgba* out)
{
  const Index v = blockIdx.x * blockDim.x + threadIdx.x;
  if (v >= vertexCount)
  {
    return;
  }
  Vec3f e = interpolateVertex(positions, normals, v, neighbours + std::size_t(v) * kInterpolants, samples,
    irradiance, harmonicDistance);
  if (caustics)
  {
    e += caustics[v];
  }
  out[v] = { e.x, e.y, e.z, 0.f };
}
}

void DevicePointTree::build(const Vec3f* p, std::uint32_t n, cudaStream_t stream)
{
  points = p;
  count = n;
  order.resize(std::max<std::uint32_t>(n, 1));
  axes.resize(std::max<std::uint32_t>(n, 1));
  if (n == 0)
  {
    return;
  }
  iotaKernel<<<gridBlocks(n), kThreads, 0, stream>>>(order.data(), n);
  axes.fillZero(stream);
  int levels = 0;
  for (std::uint32_t largest = n; largest > kTreeLeaf; largest /= 2)
  {
    ++levels;
  }
  if (levels == 0)
  {
    return;
  }
  const std::size_t widest = std::size_t(1) << levels; // ranges of the level after the last
  orderOut.resize(n);
  keys.resize(n);
  keysOut.resize(n);
  wideKeys.resize(n);
  wideKeysOut.resize(n);
  int positionBits = 1;
  while (positionBits < 32 && (std::uint64_t(1) << positionBits) < n)
  {
    ++positionBits;
  }
  for (auto* b : { &begins, &ends, &nextBegins, &nextEnds })
  {
    b->resize(widest);
  }
  rangeAxes.resize(widest);
  rootKernel<<<1, 1, 0, stream>>>(begins.data(), ends.data(), n);
  for (int level = 0; level < levels; ++level)
  {
    const std::uint32_t ranges = 1u << level;
    const bool last = level + 1 == levels;
    splitKernel<<<gridBlocks(std::size_t(ranges) * 32), kThreads, 0, stream>>>(points, order.data(), begins.data(),
      ends.data(), ranges, rangeAxes.data(), axes.data(), nextBegins.data(), nextEnds.data(), last);
    LINKGI_CUDA_CHECK_LAUNCH("splitKernel");
    if (n / ranges > kSegmentedSortBelow)
    {
      globalKeysKernel<<<gridBlocks(n), kThreads, 0, stream>>>(points, order.data(), begins.data(), ends.data(),
        ranges, rangeAxes.data(), n, wideKeys.data());
      LINKGI_CUDA_CHECK_LAUNCH("globalKeysKernel");
      cuda::sortPairs(wideKeys.data(), wideKeysOut.data(), order.data(), orderOut.data(), n, 32 + positionBits,
        temp, stream);
    }
    else
    {
      keysKernel<<<gridBlocks(n), kThreads, 0, stream>>>(points, order.data(), begins.data(), ends.data(), ranges,
        rangeAxes.data(), n, keys.data());
      LINKGI_CUDA_CHECK_LAUNCH("keysKernel");
      // Positions outside the ranges keep their entries: the sort writes only inside them.
      LINKGI_CUDA_CHECK(cudaMemcpyAsync(orderOut.data(), order.data(), n * sizeof(Index), cudaMemcpyDeviceToDevice,
        stream));
      std::size_t bytes = 0;
      LINKGI_CUDA_CHECK(cub::DeviceSegmentedSort::SortPairs(nullptr, bytes, keys.data(), keysOut.data(),
        order.data(), orderOut.data(), int(n), int(ranges), begins.data(), ends.data(), stream));
      temp.resize(std::max<std::size_t>(bytes, 1));
      LINKGI_CUDA_CHECK(cub::DeviceSegmentedSort::SortPairs(temp.data(), bytes, keys.data(), keysOut.data(),
        order.data(), orderOut.data(), int(n), int(ranges), begins.data(), ends.data(), stream));
    }
    order.swapWith(orderOut);
    begins.swapWith(nextBegins);
    ends.swapWith(nextEnds);
  }
}

PointTreeView DevicePointTree::view() const
{
  return { points, order.data(), axes.data(), count };
}

PointTreeView DevicePointTree::inTreeOrder(std::initializer_list<std::pair<const Vec3f*, Vec3f*>> arrays,
  cudaStream_t stream) const
{
  Vec3f* points = nullptr;
  for (const auto& a : arrays)
  {
    if (count)
    {
      permuteKernel<<<gridBlocks(count), kThreads, 0, stream>>>(order.data(), count, a.first, a.second);
      LINKGI_CUDA_CHECK_LAUNCH("permuteKernel");
    }
    points = points ? points : a.second;
  }
  return { points, nullptr, axes.data(), count };
}

void DevicePointTree::inTreeOrder(const float* in, float* out, cudaStream_t stream) const
{
  if (count)
  {
    permuteKernel<<<gridBlocks(count), kThreads, 0, stream>>>(order.data(), count, in, out);
    LINKGI_CUDA_CHECK_LAUNCH("permuteKernel");
  }
}

void splitPhotons(const paths::Vpl* hits, std::size_t count, DevicePhotons& out, cuda::GPUBuffer<Index>& flags,
  cuda::GPUBuffer<Offset>& scan, cuda::GPUBuffer<unsigned char>& temp, Offset* totals, cudaStream_t stream)
{
  for (auto* a : { &out.positions, &out.normals, &out.flux, &out.causticPositions, &out.causticNormals,
         &out.causticFlux })
  {
    a->resize(std::max<std::size_t>(count, 1));
  }
  flags.resize(2 * (count + 1));
  scan.resize(2 * (count + 1));
  Index* photon = flags.data();
  Index* caustic = flags.data() + count + 1;
  flags.fillZero(stream); // the entries past the last: the scans' totals
  if (count)
  {
    flagKernel<<<gridBlocks(count), kThreads, 0, stream>>>(hits, count, photon, caustic);
    LINKGI_CUDA_CHECK_LAUNCH("flagKernel");
  }
  cuda::exclusiveSum(photon, scan.data(), count + 1, temp, stream);
  cuda::exclusiveSum(caustic, scan.data() + count + 1, count + 1, temp, stream);
  if (count)
  {
    scatterKernel<<<gridBlocks(count), kThreads, 0, stream>>>(hits, count, scan.data(), scan.data() + count + 1,
      out.positions.data(), out.normals.data(), out.flux.data(), out.causticPositions.data(),
      out.causticNormals.data(), out.causticFlux.data());
    LINKGI_CUDA_CHECK_LAUNCH("scatterKernel");
  }
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(totals, scan.data() + count, sizeof(Offset), cudaMemcpyDeviceToHost, stream));
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(totals + 1, scan.data() + 2 * count + 1, sizeof(Offset),
    cudaMemcpyDeviceToHost, stream));
}

void estimateSites(const PhotonsView& photons, const Index* order, const SurfaceView& surface, std::uint32_t stride,
  std::uint32_t k, float max2, Vec3f* sitePositions, Vec3f* siteNormals, Vec3f* siteRadiance, float* siteRadius2,
  cuda::GPUBuffer<Index>& scratch, cuda::GPUBuffer<Offset>& scan, cuda::GPUBuffer<unsigned char>& temp,
  cudaStream_t stream)
{
  const std::uint32_t n = photons.tree.count;
  const std::uint32_t siteCount = (n + stride - 1) / stride;
  if (siteCount)
  {
    scratch.resize(std::size_t(n) + siteCount);
    scan.resize(n);
    Index* flags = scratch.data();
    Index* sitePhotons = scratch.data() + n;
    siteFlagKernel<<<gridBlocks(n), kThreads, 0, stream>>>(order, n, stride, flags);
    LINKGI_CUDA_CHECK_LAUNCH("siteFlagKernel");
    cuda::exclusiveSum(flags, scan.data(), n, temp, stream);
    siteOrderKernel<<<gridBlocks(n), kThreads, 0, stream>>>(order, n, stride, scan.data(), sitePhotons);
    LINKGI_CUDA_CHECK_LAUNCH("siteOrderKernel");
    withHeap<SitesLaunch>(k, photons, surface, sitePhotons, siteCount, k, max2, sitePositions, siteNormals, siteRadiance,
      siteRadius2, stream);
  }
}

void finalGather(const GatherLaunch& g, Vec3f* irradiance, float* harmonicDistance, cudaStream_t stream)
{
  if (g.clusters)
  {
    gatherKernel<<<g.clusters, kThreads, 0, stream>>>(g, irradiance, harmonicDistance);
    LINKGI_CUDA_CHECK_LAUNCH("gatherKernel");
  }
}

void interpolate(const Vec3f* positions, const Vec3f* normals, Index vertexCount, const Index* neighbours,
  const Index* samples, const Vec3f* irradiance, const float* harmonicDistance, const Vec3f* caustics,
  cuda::Rgba* out, cudaStream_t stream)
{
  if (vertexCount)
  {
    interpolateKernel<<<gridBlocks(vertexCount), kThreads, 0, stream>>>(positions, normals, vertexCount, neighbours,
      samples, irradiance, harmonicDistance, caustics, out);
    LINKGI_CUDA_CHECK_LAUNCH("interpolateKernel");
  }
}

void causticIrradiance(const PhotonsView& caustics, const Vec3f* positions, const Vec3f* normals,
  const Vec3f* albedo, const float* areas, Index vertexCount, std::uint32_t k, float max2, Vec3f* out,
  cudaStream_t stream)
{
  if (vertexCount)
  {
    withHeap<CausticLaunch>(k, caustics, positions, normals, albedo, areas, vertexCount, k, max2, out, stream);
  }
}
}
