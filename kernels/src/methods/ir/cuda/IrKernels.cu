#include "methods/ir/cuda/IrKernels.h"

#include "cuda/Primitives.h"

#include "shared/Bvh.h"

namespace linkgi::ir::gpu
{
namespace
{
constexpr int kThreads = cuda::kBlockThreads;

__global__ void gatherKernel(GatherLaunch p, cuda::Rgba* out, unsigned long long* rays)
{
  const Index elements = p.twoSided ? 2 * p.vertexCount : p.vertexCount;
  const Index i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= elements)
  {
    return;
  }
  const Index e = p.order ? p.order[i] : i;
  const Index v = e < p.vertexCount ? e : e - p.vertexCount;
  const float sign = e < p.vertexCount ? 1.f : -1.f;
  const GatherParams& gp = p.params;
  const Vec3f n = p.normals[v] * sign;
  const Vec3f x = p.positions[v] + p.origins[v].shift;
  const Vec3f origin = vertexLightOrigin(p.positions[v], p.normals[v], p.origins[v], sign);
  const std::uint32_t r = vertexSubset(v, gp.subsets, gp.seed);
  // As gatherCpu sums: the VPLs too close for the proxy to tell, then the visible ones.
  Vec3f near(0.f), far(0.f);
  unsigned long long traced = 0;
  for (std::uint32_t k = p.subsetOffsets[r]; k < p.subsetOffsets[r + 1]; ++k)
  {
    Ray ray;
    const Vec3f ek = vplIrradiance(p.vpls[k], x, origin, n, gp.dmin, ray);
    if (!(maxComponent(ek) > 0.f))
    {
      continue;
    }
    if (gp.proxyMargin > 0.f && !proxyShadowRay(ray, gp.proxyMargin))
    {
      near += ek;
      continue;
    }
    ++traced;
    Hit h;
    if (!bvh::traverse<true>(p.visibility, ray, h))
    {
      far += ek;
    }
  }
  const Vec3f sum = (near + far) * p.subsetScale[r];
  out[e] = { sum.x, sum.y, sum.z, 0.f };
  atomicAdd(rays, traced);
}

__global__ void compensateKernel(CompensationLaunch p, cuda::Rgba* out)
{
  const CompensationInputs& c = p.inputs;
  const Index elements = c.twoSided ? 2 * c.vertexCount : c.vertexCount;
  const Index e = blockIdx.x * blockDim.x + threadIdx.x;
  if (e >= elements)
  {
    return;
  }
  const Index v = e < c.vertexCount ? e : e - c.vertexCount;
  const Vec3f n = c.normals[v] * (e < c.vertexCount ? 1.f : -1.f);
  const Frame frame = vertexFrame(n, true, p.seed, e);
  const Vec3f origin = elementRayOrigin(c.positions[v], n, c.origins[v]);
  const std::uint32_t k = p.side, rays = k * k, key = compensationKey(p.seed, e);
  const auto indirectAt = [&p](Index i) {
    const cuda::Rgba x = p.indirect[i];
    return Vec3f(x.r, x.g, x.b);
  };
  const auto trace = [&p](const Ray& ray) {
    Hit h;
    bvh::traverse<false>(p.mesh, ray, h);
    return h;
  };
  const auto occluded = [&p](const Ray& ray) {
    Hit h;
    return bvh::traverse<true>(p.mesh, ray, h);
  };
  Vec3f sum(0.f);
  for (std::uint32_t i = 0; i < rays; ++i)
  {
    const Ray ray = compensationRay(origin, frame, i, k, c.dmin, key);
    sum += compensationSample(c, ray, trace(ray), indirectAt, trace, occluded);
  }
  const Vec3f total = indirectAt(e) + sum * (kPi / float(rays));
  out[e] = { total.x, total.y, total.z, 0.f };
}

using cuda::gridBlocks;

__global__ void subsetKeyKernel(Index vertexCount, Index elements, std::uint32_t subsets, std::uint32_t seed,
  std::uint64_t* keys, Index* ids)
{
  const Index e = blockIdx.x * blockDim.x + threadIdx.x;
  if (e < elements)
  {
    keys[e] = vertexSubset(e < vertexCount ? e : e - vertexCount, subsets, seed);
    ids[e] = e;
  }
}

// The proxy: cells of the vertices, sorted with the vertex numbers (stable, so a cluster's
// vertices stay in vertex order); a cluster is a run of one cell.
__global__ void cellKernel(ProxyGrid grid, const Vec3f* positions, Index n, std::uint64_t* keys, Index* ids)
{
  const Index v = blockIdx.x * blockDim.x + threadIdx.x;
  if (v < n)
  {
    keys[v] = grid.cellOf(positions[v]);
    ids[v] = v;
  }
}

/// heads[i] = 1 where sorted run i starts (i < n), 0 at n.
__global__ void headKernel(const std::uint64_t* sorted, Index n, std::uint64_t none, Index* heads)
{
  const Index i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i <= n)
  {
    heads[i] = i < n && sorted[i] != none && (i == 0 || sorted[i] != sorted[i - 1]) ? 1 : 0;
  }
}

/// cluster[vertex] and the first sorted entry of every cluster (first[clusters] = n).
__global__ void clusterKernel(const Index* order, const Index* heads, const Offset* scanned, Index n,
  Index* cluster, Index* first)
{
  const Index i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n)
  {
    const Index k = Index(scanned[i + 1] - 1);
    cluster[order[i]] = k;
    if (heads[i])
    {
      first[k] = i;
    }
  }
  else if (i == n)
  {
    first[scanned[n]] = n;
  }
}

/// A cluster at the mean of its vertices, summed in vertex order as buildProxy sums them.
__global__ void meanKernel(const Vec3f* positions, const Index* order, const Index* first,
  const Offset* scanned, Index n, Vec3f* means)
{
  const Index k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= scanned[n])
  {
    return;
  }
  Vec3f sum(0.f);
  float members = 0.f;
  for (Index j = first[k]; j < first[k + 1]; ++j)
  {
    sum += positions[order[j]];
    members += 1.f;
  }
  means[k] = sum / members;
}

constexpr std::uint64_t kDegenerate = ~std::uint64_t(0);

/// A triangle's three clusters, ordered, in one key (21 bits each); degenerate ones last.
__global__ void triangleKeyKernel(const Triangle* triangles, Index n, const Index* cluster,
  std::uint64_t* keys, Index* ids)
{
  const Index t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t >= n)
  {
    return;
  }
  Index a = cluster[triangles[t].v[0]], b = cluster[triangles[t].v[1]], c = cluster[triangles[t].v[2]];
  ids[t] = t;
  if (a == b || b == c || a == c)
  {
    keys[t] = kDegenerate;
    return;
  }
  const auto swap = [](Index& x, Index& y) {
    const Index z = x;
    x = y;
    y = z;
  };
  if (a > b) swap(a, b);
  if (b > c) swap(b, c);
  if (a > b) swap(a, b);
  keys[t] = (std::uint64_t(a) << 42) | (std::uint64_t(b) << 21) | c;
}

/// The first triangle of every run of one key, as the proxy's.
__global__ void keepKernel(const Triangle* triangles, const Index* order, const Index* heads,
  const Offset* scanned, const Index* cluster, Index n, Triangle* kept)
{
  const Index i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n && heads[i])
  {
    const Triangle& t = triangles[order[i]];
    kept[scanned[i]] = Triangle{ { cluster[t.v[0]], cluster[t.v[1]], cluster[t.v[2]] } };
  }
}
}

void compensate(const CompensationLaunch& p, cuda::Rgba* out, cudaStream_t stream)
{
  const std::size_t elements = p.inputs.twoSided ? 2 * std::size_t(p.inputs.vertexCount) : p.inputs.vertexCount;
  if (elements == 0 || p.side == 0)
  {
    return;
  }
  compensateKernel<<<unsigned((elements + kThreads - 1) / kThreads), kThreads, 0, stream>>>(p, out);
  LINKGI_CUDA_CHECK_LAUNCH("compensateKernel");
}

void gatherVpls(const GatherLaunch& p, cuda::Rgba* out, unsigned long long* rays, cudaStream_t stream)
{
  const std::size_t elements = p.twoSided ? 2 * std::size_t(p.vertexCount) : p.vertexCount;
  if (elements == 0)
  {
    return;
  }
  gatherKernel<<<unsigned((elements + kThreads - 1) / kThreads), kThreads, 0, stream>>>(p, out, rays);
  LINKGI_CUDA_CHECK_LAUNCH("gatherKernel");
}

bool DeviceProxy::fits(const ProxyGrid& grid, std::size_t vertexCount)
{
  const std::uint64_t cells = std::uint64_t(grid.resolution + 1) * (grid.resolution + 1) * (grid.resolution + 1);
  return std::min<std::uint64_t>(cells, vertexCount) <= (std::uint64_t(1) << 21);
}

void DeviceProxy::build(const ProxyGrid& grid, const Vec3f* vertexPositions, Index vertexCount,
  const Triangle* meshTriangles, Index meshTriangleCount, cudaStream_t stream)
{
  const Index nv = vertexCount, nt = meshTriangleCount;
  positionCount = triangleCount = 0;
  if (nv == 0 || nt == 0)
  {
    return;
  }
  const std::size_t most = std::max(nv, nt);
  keys.resize(most);
  sortedKeys.resize(most);
  ids.resize(most);
  order.resize(most);
  heads.resize(most + 1);
  scanned.resize(most + 1);
  cluster.resize(std::max<Index>(nv, 1));
  first.resize(nv + 1);
  sizes.resize(2);
  positions.resize(std::max<Index>(nv, 1));
  triangles.resize(std::max<Index>(nt, 1));
  // Vertices into clusters.
  cellKernel<<<gridBlocks(nv), kThreads, 0, stream>>>(grid, vertexPositions, nv, keys.data(), ids.data());
  LINKGI_CUDA_CHECK_LAUNCH("cellKernel");
  cuda::sortPairs(keys.data(), sortedKeys.data(), ids.data(), order.data(), nv, grid.cellBits(), temp, stream);
  headKernel<<<gridBlocks(nv + 1), kThreads, 0, stream>>>(sortedKeys.data(), nv, kDegenerate, heads.data());
  LINKGI_CUDA_CHECK_LAUNCH("headKernel");
  cuda::exclusiveSum(heads.data(), scanned.data(), nv + 1, temp, stream);
  clusterKernel<<<gridBlocks(nv + 1), kThreads, 0, stream>>>(order.data(), heads.data(), scanned.data(), nv,
    cluster.data(), first.data());
  LINKGI_CUDA_CHECK_LAUNCH("clusterKernel");
  meanKernel<<<gridBlocks(nv), kThreads, 0, stream>>>(vertexPositions, order.data(), first.data(), scanned.data(), nv,
    positions.data());
  LINKGI_CUDA_CHECK_LAUNCH("meanKernel");
  // Triangles between three clusters, each set of three once.
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(sizes.data(), scanned.data() + nv, sizeof(Offset), cudaMemcpyDeviceToDevice, stream));
  triangleKeyKernel<<<gridBlocks(nt), kThreads, 0, stream>>>(meshTriangles, nt, cluster.data(), keys.data(), ids.data());
  LINKGI_CUDA_CHECK_LAUNCH("triangleKeyKernel");
  cuda::sortPairs(keys.data(), sortedKeys.data(), ids.data(), order.data(), nt, 64, temp, stream);
  headKernel<<<gridBlocks(nt + 1), kThreads, 0, stream>>>(sortedKeys.data(), nt, kDegenerate, heads.data());
  LINKGI_CUDA_CHECK_LAUNCH("headKernel");
  cuda::exclusiveSum(heads.data(), scanned.data(), nt + 1, temp, stream);
  keepKernel<<<gridBlocks(nt), kThreads, 0, stream>>>(meshTriangles, order.data(), heads.data(), scanned.data(),
    cluster.data(), nt, triangles.data());
  LINKGI_CUDA_CHECK_LAUNCH("keepKernel");
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(sizes.data() + 1, scanned.data() + nt, sizeof(Offset), cudaMemcpyDeviceToDevice, stream));
  Offset counts[2] = { 0, 0 };
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(counts, sizes.data(), sizeof(counts), cudaMemcpyDeviceToHost, stream));
  LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  positionCount = Index(counts[0]);
  triangleCount = Index(counts[1]);
}

void elementsBySubset(Index vertexCount, bool twoSided, std::uint32_t subsets, std::uint32_t seed,
  cuda::GPUBuffer<std::uint64_t>& keys, cuda::GPUBuffer<Index>& ids, cuda::GPUBuffer<unsigned char>& temp,
  cuda::GPUBuffer<Index>& order, cudaStream_t stream)
{
  const Index elements = twoSided ? 2 * vertexCount : vertexCount;
  order.resize(std::max<Index>(elements, 1));
  if (elements == 0)
  {
    return;
  }
  keys.resize(2 * std::size_t(elements));
  ids.resize(elements);
  subsetKeyKernel<<<gridBlocks(elements), kThreads, 0, stream>>>(vertexCount, elements, subsets, seed, keys.data(), ids.data());
  LINKGI_CUDA_CHECK_LAUNCH("subsetKeyKernel");
  int bits = 1;
  while (bits < 32 && (1u << bits) < subsets)
  {
    ++bits;
  }
  cuda::sortPairs(keys.data(), keys.data() + elements, ids.data(), order.data(), elements, bits, temp, stream);
}
}
