// The one-ring topology, origin shifts and face normals on the GPU (DeviceTopology.h).
#include "cuda/DeviceTopology.h"

#include "cuda/Primitives.h"

#include "linkgi/Error.h"
#include "shared/Surface.h"

#include <string>

namespace linkgi::cuda
{
namespace
{
constexpr int kThreads = 256;
constexpr std::uint64_t kNoPair = ~0ull;

unsigned blocksFor(std::size_t n)
{
  return unsigned((n + kThreads - 1) / kThreads);
}

/// The six directed pairs (a, b) of each triangle as a << 32 | b; kNoPair where a == b.
__global__ void pairsKernel(const Triangle* triangles, Index count, std::uint64_t* pairs)
{
  const std::size_t t = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (t >= count)
  {
    return;
  }
  const Triangle tri = triangles[t];
  int k = 0;
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      if (i != j)
      {
        const Index a = tri.v[i], b = tri.v[j];
        pairs[6 * t + k++] = a == b ? kNoPair : (std::uint64_t(a) << 32 | b);
      }
    }
  }
}

__global__ void headsKernel(const std::uint64_t* sorted, std::size_t n, Index* heads)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n)
  {
    heads[i] = sorted[i] != kNoPair && (i == 0 || sorted[i] != sorted[i - 1]);
  }
}

/// The unique pairs, in order, into `unique` and `neighbours`; counts[0] = how many.
__global__ void compactKernel(const std::uint64_t* sorted, std::size_t n, const Index* heads,
  const Offset* at, std::uint64_t* unique, Index* neighbours, Offset* counts)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= n)
  {
    return;
  }
  if (heads[i])
  {
    unique[at[i]] = sorted[i];
    neighbours[at[i]] = Index(sorted[i]);
  }
  if (i == n - 1)
  {
    counts[0] = at[i] + heads[i];
  }
}

/// Flags the unique pairs that are edges (a < b).
__global__ void edgeFlagsKernel(const std::uint64_t* unique, std::size_t n, const Offset* counts, Index* flags)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n)
  {
    const std::uint64_t p = unique[i];
    flags[i] = i < counts[0] && Index(p) > Index(p >> 32);
  }
}

__device__ Offset lowerBound(const std::uint64_t* keys, Offset n, std::uint64_t key)
{
  Offset lo = 0, hi = n;
  while (lo < hi)
  {
    const Offset mid = (lo + hi) / 2;
    if (keys[mid] < key)
    {
      lo = mid + 1;
    }
    else
    {
      hi = mid;
    }
  }
  return lo;
}

/// Edges, each neighbour's edge, and counts[1] = edges.
__global__ void edgesKernel(const std::uint64_t* unique, std::size_t n, const Index* flags,
  const Offset* edgeAt, Offset* counts, Index* edges, Index* vertexEdges)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i == n - 1)
  {
    counts[1] = edgeAt[i] + flags[i];
  }
  if (i >= counts[0])
  {
    return;
  }
  const std::uint64_t p = unique[i];
  const Index a = Index(p >> 32), b = Index(p);
  if (b > a)
  {
    edges[2 * edgeAt[i]] = a;
    edges[2 * edgeAt[i] + 1] = b;
    vertexEdges[i] = Index(edgeAt[i]);
  }
  else
  {
    // The edge of (a, b) with b < a is b's: pair (b, a).
    vertexEdges[i] = Index(edgeAt[lowerBound(unique, counts[0], std::uint64_t(b) << 32 | a)]);
  }
}

__global__ void offsetsKernel(const std::uint64_t* unique, const Offset* counts, Index vertexCount, Index* offsets)
{
  const Index v = blockIdx.x * blockDim.x + threadIdx.x;
  if (v <= vertexCount)
  {
    offsets[v] = Index(lowerBound(unique, counts[0], std::uint64_t(v) << 32));
  }
}

__global__ void originsKernel(const Vec3f* positions, const Vec3f* normals, const Index* offsets,
  const Index* neighbours, Index vertexCount, float bound, RayOrigin* origins)
{
  const Index v = blockIdx.x * blockDim.x + threadIdx.x;
  if (v < vertexCount)
  {
    const Index begin = offsets[v];
    origins[v] = rayOrigin(positions, positions[v], normals[v], neighbours + begin, offsets[v + 1] - begin, bound);
  }
}

__global__ void faceNormalsKernel(const Vec3f* positions, const Vec3f* normals, const Triangle* triangles,
  Index count, Vec3f* out)
{
  const Index t = blockIdx.x * blockDim.x + threadIdx.x;
  if (t < count)
  {
    out[t] = frontFaceNormal(positions, normals, triangles[t]);
  }
}

int bitsFor(std::uint64_t x)
{
  int b = 0;
  while (b < 64 && (std::uint64_t(1) << b) <= x)
  {
    ++b;
  }
  return b;
}
}

DeviceTopology::DeviceTopology()
{
  void* pinned = nullptr;
  LINKGI_CUDA_CHECK(cudaMallocHost(&pinned, 2 * sizeof(Offset)));
  counts = static_cast<Offset*>(pinned);
  counts[0] = counts[1] = 0;
}

DeviceTopology::~DeviceTopology()
{
  cudaFreeHost(counts);
}

void DeviceTopology::build(const Triangle* triangles, Index triangleCount, Index vertexCount, cudaStream_t stream)
{
  const std::size_t n = 6 * std::size_t(triangleCount);
  if (n >= kInvalidIndex)
  {
    // Neighbour offsets are 32-bit, as on the CPU (Topology): a clear error, not a wrap.
    throw Error("The one-ring topology holds at most 715M triangles; got " +
      std::to_string(triangleCount) + ".");
  }
  neighbourOffsets.resize(std::size_t(vertexCount) + 1);
  deviceCounts.resize(2);
  deviceCounts.fillZero(stream);
  if (n == 0)
  {
    neighbourOffsets.fillZero(stream);
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(counts, deviceCounts.data(), 2 * sizeof(Offset), cudaMemcpyDeviceToHost, stream));
    return;
  }
  pairs.resize(n);
  sorted.resize(n);
  flags.resize(n);
  scan.resize(n);
  neighbours.resize(n); // worst case: every pair unique
  vertexEdges.resize(n);
  edges.resize(n);
  pairsKernel<<<blocksFor(triangleCount), kThreads, 0, stream>>>(triangles, triangleCount, pairs.data());
  LINKGI_CUDA_CHECK_LAUNCH("pairsKernel");
  // kNoPair has every bit set, so it sorts last on any bit range that holds the real pairs.
  sortKeys(pairs.data(), sorted.data(), n, 32 + bitsFor(vertexCount), temp, stream);
  headsKernel<<<blocksFor(n), kThreads, 0, stream>>>(sorted.data(), n, flags.data());
  LINKGI_CUDA_CHECK_LAUNCH("headsKernel");
  exclusiveSum(flags.data(), scan.data(), n, temp, stream);
  std::uint64_t* unique = pairs.data(); // the unsorted pairs are no longer needed
  compactKernel<<<blocksFor(n), kThreads, 0, stream>>>(sorted.data(), n, flags.data(), scan.data(),
    unique, neighbours.data(), deviceCounts.data());
  LINKGI_CUDA_CHECK_LAUNCH("compactKernel");
  edgeFlagsKernel<<<blocksFor(n), kThreads, 0, stream>>>(unique, n, deviceCounts.data(), flags.data());
  LINKGI_CUDA_CHECK_LAUNCH("edgeFlagsKernel");
  exclusiveSum(flags.data(), scan.data(), n, temp, stream);
  edgesKernel<<<blocksFor(n), kThreads, 0, stream>>>(unique, n, flags.data(), scan.data(),
    deviceCounts.data(), edges.data(), vertexEdges.data());
  LINKGI_CUDA_CHECK_LAUNCH("edgesKernel");
  offsetsKernel<<<blocksFor(std::size_t(vertexCount) + 1), kThreads, 0, stream>>>(unique,
    deviceCounts.data(), vertexCount, neighbourOffsets.data());
  LINKGI_CUDA_CHECK_LAUNCH("offsetsKernel");
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(counts, deviceCounts.data(), 2 * sizeof(Offset), cudaMemcpyDeviceToHost, stream));
}

void rayOrigins(const Vec3f* positions, const Vec3f* normals, const Index* neighbourOffsets,
  const Index* neighbours, Index vertexCount, float bound, RayOrigin* origins, cudaStream_t stream)
{
  if (vertexCount)
  {
    originsKernel<<<blocksFor(vertexCount), kThreads, 0, stream>>>(positions, normals, neighbourOffsets,
      neighbours, vertexCount, bound, origins);
    LINKGI_CUDA_CHECK_LAUNCH("originsKernel");
  }
}

void frontFaceNormals(const Vec3f* positions, const Vec3f* normals, const Triangle* triangles,
  Index triangleCount, Vec3f* out, cudaStream_t stream)
{
  if (triangleCount)
  {
    faceNormalsKernel<<<blocksFor(triangleCount), kThreads, 0, stream>>>(positions, normals, triangles,
      triangleCount, out);
    LINKGI_CUDA_CHECK_LAUNCH("faceNormalsKernel");
  }
}
}
