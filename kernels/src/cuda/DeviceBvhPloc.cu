// PLOC on the GPU (DeviceBvh::cluster): the agglomerative clustering that builds the BVH's
// hierarchy over the Morton-sorted triangles (DeviceBvh.cu sorts them and finishes the tree).
#include "cuda/DeviceBvh.h"
#include "cuda/DeviceBvhBuild.h"

#include "cuda/Kernels.h"
#include "cuda/Primitives.h"

#include <cub/block/block_scan.cuh>

#include <cstdlib>

namespace linkgi::cuda
{
namespace
{
using bvhbuild::blocksFor;
using bvhbuild::kThreads;

/// LINKGI_PLOC_RADIUS: the PLOC search radius (default 4). A testing knob for comparing
/// trees, read once.
int plocRadius()
{
  static const int radius = [] {
    const char* v = std::getenv("LINKGI_PLOC_RADIUS");
    const int r = v ? std::atoi(v) : 4;
    return r < 1 ? 1 : r > 32 ? 32 : r;
  }();
  return radius;
}

// PLOC (Meister & Bittner 2018): agglomerative clustering along the Morton order. Each
// cluster finds, among the `radius` clusters on either side, the one whose union box has
// the smallest surface area; mutual nearest neighbours merge into a new node; the survivors
// are compacted in order, and this repeats until one cluster is left. The tree has the
// layout of the linear BVH (leaves in Morton order, node 0 the root, parents set), so
// traversal and refit are unchanged; the child boxes are written as the nodes are made.
// Nodes are numbered from the top: with c clusters, a round's merges take the indices
// c - 2 - rank (rank: the merge's place in the Morton order), and the last one takes 0.
constexpr int kPlocMaxRadius = 32;
constexpr int kPlocTailThreads = 1024;
constexpr int kPlocTailItems = 4; ///< the last rounds, from this many clusters times the
                                  ///< block's threads, run in one block without the host

__device__ inline float halfArea(const bvh::Box& b)
{
  const float dx = b.hi.x - b.lo.x, dy = b.hi.y - b.lo.y, dz = b.hi.z - b.lo.z;
  return dx * dy + dy * dz + dz * dx;
}

__device__ inline bvh::Box unite(bvh::Box a, const bvh::Box& b)
{
  a.grow(b);
  return a;
}

/// The nearest neighbour of cluster i among [i - radius, i + radius] of c clusters, `at(j)`
/// giving cluster j's box. Pairs are ordered by (area, lower index, higher index), which
/// ascending j visits in order: the globally first pair is always mutual, so every round
/// merges at least one pair.
template <typename At>
__device__ inline int nearestCluster(int i, int c, int radius, At at)
{
  const bvh::Box own = at(i);
  float best = 3.4e38f;
  int nearest = i;
  const int last = min(c - 1, i + radius);
  for (int j = max(0, i - radius); j <= last; ++j)
  {
    if (j != i)
    {
      const float a = halfArea(unite(own, at(j)));
      if (a < best)
      {
        best = a;
        nearest = j;
      }
    }
  }
  return nearest;
}

/// Low 32 bits: the cluster survives (as itself or as the merged node); high 32: it starts a
/// merge (the lower index of a mutual pair).
__device__ inline std::uint64_t plocFlags(const int* nn, int i)
{
  const int j = nn[i];
  const bool mutual = j != i && nn[j] == i; // j == i: a lone cluster, kept
  return std::uint64_t(!mutual || i < j) | std::uint64_t(mutual && i < j) << 32;
}

/// Moves cluster i to its place among the survivors, or makes its merged node there.
/// `scanned` is the exclusive sum of plocFlags up to i.
__device__ inline void plocScatter(int i, int c, std::uint64_t scanned, const int* nn,
  const int* cluster, const bvh::Box* boxes, int* nextCluster, bvh::Box* nextBoxes, BvhNode* nodes,
  int* leafParents)
{
  const std::uint64_t f = plocFlags(nn, i);
  if (!(f & 1u))
  {
    return;
  }
  const int at = int(scanned & 0xffffffffu);
  if (!(f >> 32))
  {
    nextCluster[at] = cluster[i];
    nextBoxes[at] = boxes[i];
    return;
  }
  const int j = nn[i];
  const int node = c - 2 - int(scanned >> 32);
  const int children[2] = { cluster[i], cluster[j] };
  const bvh::Box a = boxes[i], b = boxes[j];
  BvhNode& n = nodes[node];
  bvh::storeChildBox(n, 0, a);
  bvh::storeChildBox(n, 1, b);
  n.child[0] = children[0];
  n.child[1] = children[1];
  n.pad = 0;
  if (node == 0)
  {
    n.parent = -1;
  }
  for (int k = 0; k < 2; ++k)
  {
    if (children[k] < 0)
    {
      leafParents[~children[k]] = node;
    }
    else
    {
      nodes[children[k]].parent = node;
    }
  }
  nextCluster[at] = node;
  nextBoxes[at] = unite(a, b);
}

__global__ void plocInitKernel(const BvhTriangle* tris, int n, int* cluster, bvh::Box* boxes)
{
  const int p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p < n)
  {
    cluster[p] = ~p;
    boxes[p] = bvh::triangleBox(tris[p]);
  }
}

/// One round's nearest neighbours; the block's clusters and `radius` on either side are read
/// once into shared memory.
__global__ void plocNearestKernel(const bvh::Box* boxes, const int* clusterCount, int radius, int* nn)
{
  const int c = *clusterCount;
  if (int(blockIdx.x) * kThreads >= c)
  {
    return;
  }
  constexpr int kTile = kThreads + 2 * kPlocMaxRadius;
  __shared__ float lo[3][kTile], hi[3][kTile]; // Box has constructors: no __shared__ Box
  const int first = int(blockIdx.x) * kThreads - radius;
  const int span = kThreads + 2 * radius;
  for (int k = threadIdx.x; k < span; k += kThreads)
  {
    const int j = first + k;
    if (j >= 0 && j < c)
    {
      const bvh::Box b = boxes[j];
      lo[0][k] = b.lo.x, lo[1][k] = b.lo.y, lo[2][k] = b.lo.z;
      hi[0][k] = b.hi.x, hi[1][k] = b.hi.y, hi[2][k] = b.hi.z;
    }
  }
  __syncthreads();
  const int i = blockIdx.x * kThreads + threadIdx.x;
  if (i < c)
  {
    nn[i] = nearestCluster(i, c, radius, [&](int j) {
      const int k = j - first;
      bvh::Box b;
      b.lo = { lo[0][k], lo[1][k], lo[2][k] };
      b.hi = { hi[0][k], hi[1][k], hi[2][k] };
      return b;
    });
  }
}

/// flags[c] = 0, so that the exclusive sum's element c is the round's total.
/// Over the round's bound on the count: zeros past the count.
__global__ void plocFlagsKernel(const int* nn, const int* clusterCount, int bound, std::uint64_t* flags)
{
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i <= bound)
  {
    flags[i] = i < *clusterCount ? plocFlags(nn, i) : 0;
  }
}

/// Also writes the next round's count (clusterCount[1]).
__global__ void plocScatterKernel(int* clusterCount, int bound, const std::uint64_t* scanned,
  const int* nn, const int* cluster, const bvh::Box* boxes, int* nextCluster, bvh::Box* nextBoxes,
  BvhNode* nodes, int* leafParents)
{
  const int c = clusterCount[0];
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i == 0)
  {
    clusterCount[1] = c - int(scanned[bound] >> 32);
  }
  if (i < c)
  {
    plocScatter(i, c, scanned[i], nn, cluster, boxes, nextCluster, nextBoxes, nodes, leafParents);
  }
}

/// The last rounds (c <= kPlocTailThreads * kPlocTailItems) in one block, down to the root.
/// Global memory written before __syncthreads() is seen by the whole block after it.
__global__ void __launch_bounds__(kPlocTailThreads) plocTailKernel(const int* clusterCount, int radius,
  int* nn, int* cluster, bvh::Box* boxes, int* nextCluster, bvh::Box* nextBoxes, BvhNode* nodes,
  int* leafParents)
{
  using Scan = cub::BlockScan<std::uint64_t, kPlocTailThreads>;
  __shared__ typename Scan::TempStorage scan;
  int c = *clusterCount;
  while (c > 1)
  {
    for (int i = threadIdx.x; i < c; i += kPlocTailThreads)
    {
      nn[i] = nearestCluster(i, c, radius, [&](int j) { return boxes[j]; });
    }
    __syncthreads();
    std::uint64_t f[kPlocTailItems];
    for (int k = 0; k < kPlocTailItems; ++k)
    {
      const int i = threadIdx.x * kPlocTailItems + k;
      f[k] = i < c ? plocFlags(nn, i) : 0;
    }
    std::uint64_t total;
    Scan(scan).ExclusiveSum(f, f, total);
    for (int k = 0; k < kPlocTailItems; ++k)
    {
      const int i = threadIdx.x * kPlocTailItems + k;
      if (i < c)
      {
        plocScatter(i, c, f[k], nn, cluster, boxes, nextCluster, nextBoxes, nodes, leafParents);
      }
    }
    __syncthreads();
    c -= int(total >> 32);
    int* t = cluster;
    cluster = nextCluster;
    nextCluster = t;
    bvh::Box* b = boxes;
    boxes = nextBoxes;
    nextBoxes = b;
  }
}
}

void DeviceBvh::cluster(cudaStream_t stream)
{
  const int n = int(count);
  const int radius = plocRadius();
  for (GPUBuffer<int>* b : { &clusters[0], &clusters[1], &nearest })
  {
    b->resize(count);
  }
  clusterBoxes[0].resize(count);
  clusterBoxes[1].resize(count);
  flags.resize(count + 1);
  scanned.resize(count + 1);
  plocInitKernel<<<blocksFor(count), kThreads, 0, stream>>>(triangles.data(), n,
    clusters[0].data(), clusterBoxes[0].data());
  LINKGI_CUDA_CHECK_LAUNCH("plocInitKernel");
  // Rounds with many clusters: one kernel per step, the counts on the device (round k reads
  // counts[k], writes counts[k + 1]); the host reads the count every kPlocRoundsPerRead rounds
  // only, sizing the launches by the last count it read.
  constexpr int kPlocRoundsPerRead = 4;
  roundCounts.resize(kPlocRoundsPerRead + 1);
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(roundCounts.data(), &n, sizeof(int), cudaMemcpyHostToDevice, stream));
  int bound = n, from = 0;
  while (bound > kPlocTailThreads * kPlocTailItems)
  {
    for (int k = 0; k < kPlocRoundsPerRead; ++k)
    {
      const int to = 1 - from;
      int* count = roundCounts.data() + k;
      plocNearestKernel<<<blocksFor(bound), kThreads, 0, stream>>>(clusterBoxes[from].data(), count,
        radius, nearest.data());
      LINKGI_CUDA_CHECK_LAUNCH("plocNearestKernel");
      plocFlagsKernel<<<blocksFor(bound + 1), kThreads, 0, stream>>>(nearest.data(), count, bound, flags.data());
      LINKGI_CUDA_CHECK_LAUNCH("plocFlagsKernel");
      exclusiveSum(flags.data(), scanned.data(), std::size_t(bound) + 1, temp, stream);
      plocScatterKernel<<<blocksFor(bound), kThreads, 0, stream>>>(count, bound, scanned.data(),
        nearest.data(), clusters[from].data(), clusterBoxes[from].data(), clusters[to].data(),
        clusterBoxes[to].data(), nodes.data(), leafParents.data());
      LINKGI_CUDA_CHECK_LAUNCH("plocScatterKernel");
      from = to;
    }
    int* last = roundCounts.data() + kPlocRoundsPerRead;
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(&bound, last, sizeof(int), cudaMemcpyDeviceToHost, stream));
    LINKGI_CUDA_CHECK(cudaMemcpyAsync(roundCounts.data(), last, sizeof(int), cudaMemcpyDeviceToDevice, stream));
    LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  }
  plocTailKernel<<<1, kPlocTailThreads, 0, stream>>>(roundCounts.data(), radius, nearest.data(),
    clusters[from].data(), clusterBoxes[from].data(), clusters[1 - from].data(),
    clusterBoxes[1 - from].data(), nodes.data(), leafParents.data());
  LINKGI_CUDA_CHECK_LAUNCH("plocTailKernel");
}
}
