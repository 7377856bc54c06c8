#include "DeviceBvh.h"

#include "Kernels.h"
#include "Primitives.h"

#include <cub/block/block_scan.cuh>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace linkgi::cuda
{
namespace
{
constexpr int kThreads = 256;

unsigned blocksFor(std::size_t n, int threads = kThreads)
{
  return unsigned((n + threads - 1) / threads);
}

/// LINKGI_CUDA_BVH=linear: the linear BVH (Karras) instead of PLOC; LINKGI_PLOC_RADIUS: the
/// PLOC search radius (default 4). Testing knobs for comparing trees, read once.
bool linearBvhRequested()
{
  static const bool linear = [] {
    const char* v = std::getenv("LINKGI_CUDA_BVH");
    return v && std::strcmp(v, "linear") == 0;
  }();
  return linear;
}

/// LINKGI_CUDA_BVH_ORDER=build keeps the builder's node order (no depth-first reordering);
/// LINKGI_CUDA_BVH_COST=1 prints each build's surface-area cost to stderr.
bool depthFirstOrder()
{
  static const bool on = [] {
    const char* v = std::getenv("LINKGI_CUDA_BVH_ORDER");
    return !(v && std::strcmp(v, "build") == 0);
  }();
  return on;
}

bool printCost()
{
  static const bool on = std::getenv("LINKGI_CUDA_BVH_COST") != nullptr;
  return on;
}

int plocRadius()
{
  static const int radius = [] {
    const char* v = std::getenv("LINKGI_PLOC_RADIUS");
    const int r = v ? std::atoi(v) : 4;
    return r < 1 ? 1 : r > 32 ? 32 : r;
  }();
  return radius;
}

/// Block-wide union of per-thread boxes into out[blockIdx.x].
__device__ void reduceBox(bvh::Box box, bvh::Box* out)
{
  __shared__ float lo[3][kThreads], hi[3][kThreads];
  const int t = threadIdx.x;
  lo[0][t] = box.lo.x, lo[1][t] = box.lo.y, lo[2][t] = box.lo.z;
  hi[0][t] = box.hi.x, hi[1][t] = box.hi.y, hi[2][t] = box.hi.z;
  __syncthreads();
  for (int s = kThreads / 2; s > 0; s /= 2)
  {
    if (t < s)
    {
      for (int a = 0; a < 3; ++a)
      {
        lo[a][t] = fminf(lo[a][t], lo[a][t + s]);
        hi[a][t] = fmaxf(hi[a][t], hi[a][t + s]);
      }
    }
    __syncthreads();
  }
  if (t == 0)
  {
    out[blockIdx.x].lo = { lo[0][0], lo[1][0], lo[2][0] };
    out[blockIdx.x].hi = { hi[0][0], hi[1][0], hi[2][0] };
  }
}

__global__ void pointBoxKernel(const Vec3f* points, Index n, bvh::Box* partial)
{
  bvh::Box box;
  for (Index i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x)
  {
    box.grow(points[i]);
  }
  reduceBox(box, partial);
}

__global__ void boxUnionKernel(const bvh::Box* partial, Index n, bvh::Box* out)
{
  bvh::Box box;
  for (Index i = threadIdx.x; i < n; i += blockDim.x)
  {
    box.grow(partial[i]);
  }
  reduceBox(box, out);
}

__global__ void mortonKernel(const Vec3f* positions, const Triangle* triangles, Index n,
  const bvh::Box* sceneBox, std::uint64_t* keys, Index* values)
{
  const Index i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i >= n)
  {
    return;
  }
  const bvh::Box box = *sceneBox;
  const Vec3f extent = box.hi - box.lo;
  const Vec3f inv(extent.x > 0.f ? 1.f / extent.x : 0.f, extent.y > 0.f ? 1.f / extent.y : 0.f,
    extent.z > 0.f ? 1.f / extent.z : 0.f);
  const Triangle t = triangles[i];
  keys[i] = bvh::mortonKey(positions[t.v[0]], positions[t.v[1]], positions[t.v[2]], box.lo, inv);
  values[i] = i;
}

__global__ void gatherTrianglesKernel(const Vec3f* positions, const Triangle* triangles,
  const Index* order, Index n, BvhTriangle* out)
{
  const Index p = blockIdx.x * blockDim.x + threadIdx.x;
  if (p < n)
  {
    const Index id = order[p];
    const Triangle t = triangles[id];
    out[p] = bvh::makeTriangle(positions[t.v[0]], positions[t.v[1]], positions[t.v[2]], id);
  }
}

__global__ void hierarchyKernel(const std::uint64_t* keys, int n, BvhNode* nodes, int* leafParents)
{
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n - 1)
  {
    bvh::buildInternalNode(keys, n, i, nodes, leafParents);
  }
}

__global__ void boundsKernel(BvhNode* nodes, const int* leafParents, const BvhTriangle* tris,
  unsigned* arrivals, int n)
{
  const int leaf = blockIdx.x * blockDim.x + threadIdx.x;
  if (leaf < n)
  {
    bvh::propagateBounds(nodes, leafParents, tris, arrivals, leaf);
  }
}

__device__ inline float boxArea(float lx, float hx, float ly, float hy, float lz, float hz)
{
  const float dx = hx - lx, dy = hy - ly, dz = hz - lz;
  return 2.f * (dx * dy + dy * dz + dz * dx);
}

/// Per block, in a fixed order: the summed child box areas of nodes i = block, block + grid...
__global__ void areaKernel(const BvhNode* nodes, int n, double* partial)
{
  __shared__ double sum[kThreads];
  double a = 0.0;
  for (int i = blockIdx.x * blockDim.x + threadIdx.x; i < n; i += gridDim.x * blockDim.x)
  {
    const BvhNode& b = nodes[i];
    a += boxArea(b.lo0x, b.hi0x, b.lo0y, b.hi0y, b.lo0z, b.hi0z) +
      boxArea(b.lo1x, b.hi1x, b.lo1y, b.hi1y, b.lo1z, b.hi1z);
  }
  sum[threadIdx.x] = a;
  __syncthreads();
  for (int s = kThreads / 2; s > 0; s /= 2)
  {
    if (threadIdx.x < s)
    {
      sum[threadIdx.x] += sum[threadIdx.x + s];
    }
    __syncthreads();
  }
  if (threadIdx.x == 0)
  {
    partial[blockIdx.x] = sum[0];
  }
  if (blockIdx.x == 0 && threadIdx.x == 0)
  {
    const BvhNode& r = nodes[0];
    partial[gridDim.x] = boxArea(fminf(r.lo0x, r.lo1x), fmaxf(r.hi0x, r.hi1x), fminf(r.lo0y, r.lo1y),
      fmaxf(r.hi0y, r.hi1y), fminf(r.lo0z, r.lo1z), fmaxf(r.hi0z, r.hi1z));
  }
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

// Depth-first order of a finished tree: each node's first child right after it, its second
// after the first's subtree, leaves (and their triangles) in the order traversal meets them.
// PLOC numbers nodes by round, so a node's children and triangles lie far from it; in this
// order a subtree is one contiguous range of nodes and one of triangles.

/// Internal nodes below each node (itself included), bottom-up as the bounds are.
__global__ void subtreeSizeKernel(const BvhNode* nodes, const int* leafParents, unsigned* arrivals,
  int* sizes, int n)
{
  const int leaf = blockIdx.x * blockDim.x + threadIdx.x;
  if (leaf >= n)
  {
    return;
  }
  int node = leafParents[leaf];
  while (node >= 0)
  {
    __threadfence();
    if (atomicAdd(&arrivals[node], 1u) == 0)
    {
      return;
    }
    __threadfence();
    const int c0 = nodes[node].child[0], c1 = nodes[node].child[1];
    sizes[node] = 1 + (c0 >= 0 ? __ldcg(&sizes[c0]) : 0) + (c1 >= 0 ? __ldcg(&sizes[c1]) : 0);
    node = nodes[node].parent;
  }
}

/// Depth-first position of internal node x (x >= 0) or of leaf ~x, from the path to the root:
/// one step per level, plus the left sibling's subtree wherever the path is a second child.
__device__ inline int depthFirstPosition(const BvhNode* nodes, const int* leafParents,
  const int* sizes, int x)
{
  const bool leaf = x < 0;
  int position = 0;
  int child = x;
  int parent = leaf ? leafParents[~x] : nodes[x].parent;
  while (parent >= 0)
  {
    const int c0 = nodes[parent].child[0];
    position += leaf ? 0 : 1;
    if (c0 != child)
    {
      // Internal nodes count the sibling's internal nodes; leaves its leaves (internal + 1).
      position += c0 >= 0 ? sizes[c0] + (leaf ? 1 : 0) : (leaf ? 1 : 0);
    }
    child = parent;
    parent = nodes[parent].parent;
  }
  return position;
}

__global__ void depthFirstKernel(const BvhNode* nodes, const int* leafParents, const int* sizes,
  int n, int* nodeAt, int* leafAt)
{
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n - 1)
  {
    nodeAt[i] = depthFirstPosition(nodes, leafParents, sizes, i);
  }
  if (i < n)
  {
    leafAt[i] = depthFirstPosition(nodes, leafParents, sizes, ~i);
  }
}

__global__ void reorderKernel(const BvhNode* nodes, const int* leafParents, const Index* order,
  const BvhTriangle* tris, const int* nodeAt, const int* leafAt, int n, BvhNode* outNodes,
  int* outLeafParents, Index* outOrder, BvhTriangle* outTris)
{
  const int i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < n - 1)
  {
    BvhNode node = nodes[i];
    for (int k = 0; k < 2; ++k)
    {
      node.child[k] = node.child[k] >= 0 ? nodeAt[node.child[k]] : ~leafAt[~node.child[k]];
    }
    node.parent = node.parent >= 0 ? nodeAt[node.parent] : -1;
    outNodes[nodeAt[i]] = node;
  }
  if (i < n)
  {
    const int at = leafAt[i];
    outLeafParents[at] = nodeAt[leafParents[i]];
    outOrder[at] = order[i];
    outTris[at] = tris[i];
  }
}

__global__ void traceKernel(BvhView bvh, const Ray* rays, Hit* hits, std::size_t n)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n)
  {
    Hit h;
    bvh::traverse<false>(bvh, rays[i], h);
    hits[i] = h;
  }
}

__global__ void occludedKernel(BvhView bvh, const Ray* rays, std::uint8_t* occluded, std::size_t n)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < n)
  {
    Hit h;
    occluded[i] = bvh::traverse<true>(bvh, rays[i], h) ? 1 : 0;
  }
}
}

void DeviceBvh::build(const Vec3f* positions, Index vertexCount, const Triangle* tris,
  Index triangleCount, cudaStream_t stream)
{
  count = triangleCount;
  if (count == 0)
  {
    return;
  }
  const unsigned partials = std::min(1024u, blocksFor(vertexCount));
  boxes.resize(partials + 1);
  pointBoxKernel<<<partials, kThreads, 0, stream>>>(positions, vertexCount, boxes.data());
  LINKGI_CUDA_CHECK_LAUNCH("pointBoxKernel");
  boxUnionKernel<<<1, kThreads, 0, stream>>>(boxes.data(), partials, boxes.data() + partials);
  LINKGI_CUDA_CHECK_LAUNCH("boxUnionKernel");

  keys.resize(count);
  sortedKeys.resize(count);
  ids.resize(count);
  mortonKernel<<<blocksFor(count), kThreads, 0, stream>>>(positions, tris, count,
    boxes.data() + partials, keys.data(), ids.data());
  LINKGI_CUDA_CHECK_LAUNCH("mortonKernel");
  order.resize(count);
  sortPairs(keys.data(), sortedKeys.data(), ids.data(), order.data(), count, 64, temp, stream);

  nodes.resize(count > 1 ? count - 1 : 1);
  leafParents.resize(count);
  arrivals.resize(nodes.size());
  const bool ploc = count > 1 && !linearBvhRequested();
  if (ploc)
  {
    cluster(positions, tris, stream);
  }
  else
  {
    if (count > 1)
    {
      hierarchyKernel<<<blocksFor(count - 1), kThreads, 0, stream>>>(sortedKeys.data(), int(count),
        nodes.data(), leafParents.data());
      LINKGI_CUDA_CHECK_LAUNCH("hierarchyKernel");
    }
    gatherAndBound(positions, tris, stream);
  }
  if (count > 2 && depthFirstOrder())
  {
    reorderDepthFirst(stream);
  }
  if (printCost())
  {
    std::fprintf(stderr, "linkgi bvh: %s%s, %u triangles, cost %.3f\n", ploc ? "ploc" : "linear",
      depthFirstOrder() ? " depth-first" : "", unsigned(count), cost(stream));
  }
}

void DeviceBvh::reorderDepthFirst(cudaStream_t stream)
{
  const int n = int(count);
  GPUBuffer<int>& sizes = clusters[0];
  GPUBuffer<int>& nodeAt = clusters[1];
  GPUBuffer<int>& leafAt = nearest;
  for (GPUBuffer<int>* b : { &sizes, &nodeAt, &leafAt })
  {
    b->resize(count);
  }
  reordered.resize(nodes.size());
  reorderedLeafParents.resize(count);
  reorderedOrder.resize(count);
  reorderedTriangles.resize(count);
  arrivals.fillZero(stream);
  subtreeSizeKernel<<<blocksFor(count), kThreads, 0, stream>>>(nodes.data(), leafParents.data(),
    arrivals.data(), sizes.data(), n);
  LINKGI_CUDA_CHECK_LAUNCH("subtreeSizeKernel");
  depthFirstKernel<<<blocksFor(count), kThreads, 0, stream>>>(nodes.data(), leafParents.data(),
    sizes.data(), n, nodeAt.data(), leafAt.data());
  LINKGI_CUDA_CHECK_LAUNCH("depthFirstKernel");
  reorderKernel<<<blocksFor(count), kThreads, 0, stream>>>(nodes.data(), leafParents.data(),
    order.data(), triangles.data(), nodeAt.data(), leafAt.data(), n, reordered.data(),
    reorderedLeafParents.data(), reorderedOrder.data(), reorderedTriangles.data());
  LINKGI_CUDA_CHECK_LAUNCH("reorderKernel");
  nodes.swapWith(reordered);
  leafParents.swapWith(reorderedLeafParents);
  order.swapWith(reorderedOrder);
  triangles.swapWith(reorderedTriangles);
}

void DeviceBvh::cluster(const Vec3f* positions, const Triangle* tris, cudaStream_t stream)
{
  const int n = int(count);
  const int radius = plocRadius();
  triangles.resize(count);
  gatherTrianglesKernel<<<blocksFor(count), kThreads, 0, stream>>>(positions, tris, order.data(),
    count, triangles.data());
  LINKGI_CUDA_CHECK_LAUNCH("gatherTrianglesKernel");
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

void DeviceBvh::upload(const HostBvh& tree, const Vec3f* positions, const Triangle* tris,
  cudaStream_t stream)
{
  count = Index(tree.triangles.size());
  std::vector<Index> leaves(count);
  for (Index p = 0; p < count; ++p)
  {
    leaves[p] = tree.triangles[p].id;
  }
  order.upload(leaves, stream);
  nodes.upload(tree.nodes, stream);
  leafParents.upload(tree.leafParents, stream);
  arrivals.resize(nodes.size());
  gatherAndBound(positions, tris, stream);
  LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream)); // `leaves` lives on this stack frame
  if (printCost())
  {
    std::fprintf(stderr, "linkgi bvh: host, %u triangles, cost %.3f\n", unsigned(count), cost(stream));
  }
}

void DeviceBvh::refit(const Vec3f* positions, const Triangle* tris, cudaStream_t stream)
{
  if (count > 0)
  {
    gatherAndBound(positions, tris, stream);
  }
}

void DeviceBvh::gatherAndBound(const Vec3f* positions, const Triangle* tris, cudaStream_t stream)
{
  triangles.resize(count);
  gatherTrianglesKernel<<<blocksFor(count), kThreads, 0, stream>>>(positions, tris, order.data(),
    count, triangles.data());
  LINKGI_CUDA_CHECK_LAUNCH("gatherTrianglesKernel");
  if (count > 1)
  {
    arrivals.fillZero(stream);
    boundsKernel<<<blocksFor(count), kThreads, 0, stream>>>(nodes.data(), leafParents.data(),
      triangles.data(), arrivals.data(), int(count));
    LINKGI_CUDA_CHECK_LAUNCH("boundsKernel");
  }
}

double DeviceBvh::cost(cudaStream_t stream)
{
  if (count < 2)
  {
    return 1.0;
  }
  constexpr unsigned kBlocks = 128;
  areas.resize(kBlocks + 1);
  areaKernel<<<kBlocks, kThreads, 0, stream>>>(nodes.data(), int(count - 1), areas.data());
  LINKGI_CUDA_CHECK_LAUNCH("areaKernel");
  double host[kBlocks + 1];
  LINKGI_CUDA_CHECK(cudaMemcpyAsync(host, areas.data(), sizeof(host), cudaMemcpyDeviceToHost, stream));
  LINKGI_CUDA_CHECK(cudaStreamSynchronize(stream));
  double sum = 0.0;
  for (unsigned b = 0; b < kBlocks; ++b)
  {
    sum += host[b];
  }
  return host[kBlocks] > 0.0 ? sum / host[kBlocks] : 1.0;
}

BvhView DeviceBvh::view() const
{
  BvhView v;
  v.nodes = nodes.data();
  v.triangles = triangles.data();
  v.root = count > 1 ? 0 : ~0;
  v.triangleCount = count;
  return v;
}

std::size_t DeviceBvh::bytes() const
{
  return nodes.bytes() + triangles.bytes() + leafParents.bytes() + arrivals.bytes() +
    order.bytes() + boxes.bytes() + temp.bytes() + keys.bytes() + sortedKeys.bytes() + ids.bytes() +
    clusters[0].bytes() + clusters[1].bytes() + clusterBoxes[0].bytes() + clusterBoxes[1].bytes() +
    nearest.bytes() + flags.bytes() + scanned.bytes() + roundCounts.bytes() + reordered.bytes() +
    reorderedLeafParents.bytes() + reorderedOrder.bytes() + reorderedTriangles.bytes();
}

void traceRays(const BvhView& bvh, const Ray* rays, Hit* hits, std::size_t count, cudaStream_t stream)
{
  if (count)
  {
    traceKernel<<<blocksFor(count), kThreads, 0, stream>>>(bvh, rays, hits, count);
    LINKGI_CUDA_CHECK_LAUNCH("traceKernel");
  }
}

void occludedRays(const BvhView& bvh, const Ray* rays, std::uint8_t* occluded, std::size_t count,
  cudaStream_t stream)
{
  if (count)
  {
    occludedKernel<<<blocksFor(count), kThreads, 0, stream>>>(bvh, rays, occluded, count);
    LINKGI_CUDA_CHECK_LAUNCH("occludedKernel");
  }
}
}
