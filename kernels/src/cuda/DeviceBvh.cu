#include "cuda/DeviceBvh.h"
#include "cuda/DeviceBvhBuild.h"

#include "cuda/Kernels.h"
#include "cuda/Primitives.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace linkgi::cuda
{
namespace
{
using bvhbuild::blocksFor;
using bvhbuild::kThreads;

/// LINKGI_CUDA_BVH=linear: the linear BVH (Karras) instead of PLOC (DeviceBvhPloc.cu). A
/// testing knob for comparing trees, read once.
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
    triangles.resize(count);
    gatherTrianglesKernel<<<blocksFor(count), kThreads, 0, stream>>>(positions, tris, order.data(),
      count, triangles.data());
    LINKGI_CUDA_CHECK_LAUNCH("gatherTrianglesKernel");
    cluster(stream);
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
