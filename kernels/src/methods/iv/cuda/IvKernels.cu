#include "methods/iv/cuda/IvKernels.h"
#include "methods/iv/ImplicitLinks.h"

#include "cuda/Primitives.h"

#include "shared/Bounce.h"
#include "shared/Gaps.h"

namespace linkgi::iv::gpu
{
namespace
{
using cuda::Rgba;
using cuda::toRgba;
using cuda::toVec;
constexpr int kThreads = cuda::kBlockThreads;
/// Threads of the push's block per leaf.
constexpr int kPushThreads = 128;
/// Leaves a leaf draws from their surface (near ones and wide ones seen from behind, through
/// every ancestor's links, each once).
constexpr int kMaxSurfaceLeaves = 2048;

using cuda::gridBlocks;

struct Append
{
  PairList list;
  __device__ void operator()(Index a, Index b) const
  {
    const unsigned long long i = atomicAdd(list.count, 1ull);
    if (i < list.capacity)
    {
      list.out[i] = { a, b };
    }
  }
};

__global__ void visitKernel(PairRules rules, const NodePair* frontier, std::size_t count, PairList next, PairList links)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= count)
  {
    return;
  }
  Append emit{ links }, push{ next };
  rules.visit(frontier[i].a, frontier[i].b, emit, push);
}

__global__ void binKernel(const NodePair* links, std::size_t count, const NodeBounds* nodes, const float* extents,
  int n, int binCount, float binAngle, std::uint64_t* best, Index* zeroCounts, NodePair* zero,
  unsigned long long* zeroCount)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= count)
  {
    return;
  }
  const NodePair l = links[i];
  const Vec3f d = nodes[l.b].position - nodes[l.a].position;
  const float d2 = dot(d, d);
  const NodeBounds& source = nodes[l.b];
  const bool leaf = source.firstChild == kInvalidIndex;
  if (!(d2 > 0.f) || keptWhole(leaf, source.radius, leaf ? extents[l.b] : 0.f, source.normal, d, d2, binAngle))
  {
    // No direction, or a leaf the push draws from its surface: kept. (The row's order does
    // not matter to the push.)
    atomicAdd(&zeroCounts[l.a], 1u);
    zero[atomicAdd(zeroCount, 1ull)] = l;
    return;
  }
  atomicMin(reinterpret_cast<unsigned long long*>(&best[std::size_t(l.a) * binCount + cubeBin(d, n)]),
    (unsigned long long)binKey(d2, l.b));
}

__global__ void countRowsKernel(const std::uint64_t* best, std::size_t nodes, int binCount, const Index* zeroCounts,
  Index* binCounts, Index* rowCounts)
{
  const std::size_t node = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (node >= nodes)
  {
    return;
  }
  Index c = 0;
  for (int b = 0; b < binCount; ++b)
  {
    c += best[node * binCount + b] != kEmptyBin;
  }
  binCounts[node] = c;
  rowCounts[node] = c + zeroCounts[node];
}

__global__ void writeRowsKernel(const std::uint64_t* best, std::size_t nodes, int binCount, const Offset* rowStarts,
  const Index* binCounts, Index* columns, Offset* cursor)
{
  const std::size_t node = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (node >= nodes)
  {
    return;
  }
  Offset out = rowStarts[node];
  for (int b = 0; b < binCount; ++b)
  {
    const std::uint64_t key = best[node * binCount + b];
    if (key != kEmptyBin)
    {
      columns[out++] = Index(key & 0xffffffffu);
    }
  }
  cursor[node] = rowStarts[node] + binCounts[node];
}

__global__ void writeZeroKernel(const NodePair* zero, const unsigned long long* zeroCount, Offset* cursor, Index* columns)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i < *zeroCount)
  {
    columns[atomicAdd(reinterpret_cast<unsigned long long*>(&cursor[zero[i].a]), 1ull)] = zero[i].b;
  }
}

/// One leaf's bins in shared memory: every candidate is an atomic minimum of its key.
struct LeafBins
{
  const NodeBounds* nodes;
  int binsPerSide;
  std::uint64_t* keys;
  Vec3f at, normal;
  Index node = 0, leaf = 0, source = 0;

  /// A point q of `source`, its bin known (>= 0: the link's own at an ancestor) or not.
  __device__ void offer(const Vec3f& q, int bin) const
  {
    const Vec3f d = q - at;
    const float d2 = dot(d, d);
    if (!(d2 > 0.f) || dot(normal, d) <= 0.f)
    {
      return; // behind this leaf's plane, though its ancestor could see it
    }
    if (bin < 0)
    {
      const Vec3f binned = node == leaf ? d : q - nodes[node].position;
      bin = cubeBin(dot(binned, binned) > 0.f ? binned : d, binsPerSide);
    }
    atomicMin(reinterpret_cast<unsigned long long*>(&keys[bin]), (unsigned long long)binKey(d2, source));
  }
  __device__ void operator()(const Vec3f& q) const { offer(q, -1); }
};

/// Sorts `count` (a power of two) keys in shared memory, ascending.
__device__ void bitonicSort(std::uint64_t* keys, int count)
{
  for (int k = 2; k <= count; k <<= 1)
  {
    for (int j = k >> 1; j > 0; j >>= 1)
    {
      for (int i = threadIdx.x; i < count; i += blockDim.x)
      {
        const int partner = i ^ j;
        if (partner > i)
        {
          const std::uint64_t a = keys[i], b = keys[partner];
          if ((a > b) == ((i & k) == 0))
          {
            keys[i] = b;
            keys[partner] = a;
          }
        }
      }
      __syncthreads();
    }
  }
}

/// Sorts the bins' (column, bin) keys and writes the row, equal columns merged (weights
/// summed in bin order), scaled by `scale`. Returns the row's length (thread 0).
__device__ Index writeRow(std::uint64_t* sortKeys, int padded, const float* binWeights, float scale,
  Index* columns, float* weights)
{
  bitonicSort(sortKeys, padded);
  Index count = 0;
  if (threadIdx.x == 0)
  {
    for (int i = 0; i < padded && sortKeys[i] != kEmptyBin; ++i)
    {
      const Index column = Index(sortKeys[i] >> 32);
      const float w = binWeights[sortKeys[i] & 0xffffffffu] * scale;
      if (count > 0 && columns[count - 1] == column)
      {
        weights[count - 1] += w;
      }
      else
      {
        columns[count] = column;
        weights[count] = w;
        ++count;
      }
    }
  }
  __syncthreads();
  return count;
}

__global__ void __launch_bounds__(kPushThreads) pushKernel(PushParams p, std::size_t stride, Offset* rowStarts, Index* counts, Index* envCounts, Index* columns, float* weights, Index* envColumns,
  float* envWeights, unsigned long long* totals)
{
  extern __shared__ std::uint64_t shared[];
  const int binCount = 6 * p.binsPerSide * p.binsPerSide;
  int padded = 1;
  while (padded < binCount)
  {
    padded <<= 1;
  }
  std::uint64_t* keys = shared;                   // binCount
  std::uint64_t* sortKeys = shared + binCount;    // padded
  float* binWeights = reinterpret_cast<float*>(sortKeys + padded); // binCount
  Index* near = reinterpret_cast<Index*>(binWeights + binCount);   // kMaxSurfaceLeaves
  __shared__ int nearCount;
  __shared__ float hemisphere;
  __shared__ unsigned occupied, empty;

  const Index leaf = blockIdx.x;
  for (int b = threadIdx.x; b < binCount; b += blockDim.x)
  {
    keys[b] = kEmptyBin;
  }
  if (threadIdx.x == 0)
  {
    nearCount = 0;
    occupied = empty = 0;
  }
  __syncthreads();

  LeafBins bins{ p.nodes, p.binsPerSide, keys };
  bins.leaf = leaf;
  bins.normal = p.nodes[leaf].normal;
  bins.at = p.receivers ? p.nodes[leaf].position + p.receivers[leaf].shift : p.nodes[leaf].position;
  for (Index node = leaf; node != kInvalidIndex; node = p.parent[node])
  {
    bins.node = node;
    const Offset first = p.rowStarts[node];
    // What the nearer ancestors listed (a node's row names a source once; its ancestors may
    // name it again).
    const int listedBefore = nearCount < kMaxSurfaceLeaves ? nearCount : kMaxSurfaceLeaves;
    for (Index e = threadIdx.x; e < p.rowCounts[node]; e += blockDim.x)
    {
      const Index src = p.columns[first + e];
      bins.source = src;
      const NodeBounds& s = p.nodes[src];
      // A link pushed down keeps the bin it has at its node (as in the paper).
      int bin = -1;
      if (node != leaf)
      {
        const Vec3f d = s.position - p.nodes[node].position;
        bin = dot(d, d) > 0.f ? cubeBin(d, p.binsPerSide) : -1;
      }
      bins.offer(s.position, bin);
      if (src < p.leafCount)
      {
        const Vec3f toSource = s.position - bins.at;
        const float r2 = dot(toSource, toSource);
        const LeafReach reach = leafReach(s.radius, p.extents[src], r2, p.binAngle, -dot(s.normal, toSource));
        bool listed = false;
        for (int i = 0; reach == LeafReach::Surface && i < listedBefore && !listed; ++i)
        {
          listed = near[i] == src;
        }
        if (reach == LeafReach::Surface && !listed)
        {
          // A neighbour, a twin, a surface across a contact or behind.
          const int slot = atomicAdd(&nearCount, 1);
          if (slot < kMaxSurfaceLeaves)
          {
            near[slot] = src;
          }
        }
        else if (reach == LeafReach::Splat)
        {
          splatDisc(s.position, s.normal, s.radius, std::sqrt(r2), p.binAngle, bins);
        }
      }
    }
    __syncthreads(); // this node's list complete before the next one reads it
  }
  if (nearCount > kMaxSurfaceLeaves)
  {
    if (threadIdx.x == 0)
    {
      atomicAdd(&totals[4], 1ull);
    }
    return; // the host refuses the result (the CPU runs the update)
  }
  // Leaves drawn from their surface: every bin whose centre ray meets one of their
  // triangles' parts takes them at the hit's distance, a back as such (one thread per bin).
  const Vec3f origin = p.receivers ? bins.at + bins.normal * p.receivers[leaf].offset : bins.at;
  for (int b = threadIdx.x; b < binCount; b += blockDim.x)
  {
    const Vec3f dir = p.binCenters[b];
    if (nearCount == 0 || dot(dir, bins.normal) <= 0.f)
    {
      continue;
    }
    std::uint64_t best = keys[b];
    float bestT = 0.f; // of a surface hit that is the best
    Index bestTriangle = kInvalidIndex;
    float bestU = 0.f, bestV = 0.f;
    for (int i = 0; i < nearCount; ++i)
    {
      const Index src = near[i];
      for (Index k = p.elementOffsets[src]; k < p.elementOffsets[src + 1]; ++k)
      {
        const Triangle tri = p.triangles[p.elementTriangles[k]];
        const int corner = tri.v[0] == src ? 0 : tri.v[1] == src ? 1 : 2;
        bool back = false;
        float u, v;
        const float t = surfaceHit(origin, dir, p.positions[tri.v[0]], p.positions[tri.v[1]], p.positions[tri.v[2]],
          corner, p.faceNormals[p.elementTriangles[k]], back, u, v);
        if (t > 0.f)
        {
          const std::uint64_t key = binKey(t * t, src | kSurfaceHit | (back ? kSurfaceBack : 0u));
          if (key < best)
          {
            best = key;
            bestT = t;
            bestTriangle = p.elementTriangles[k];
            bestU = u;
            bestV = v;
          }
        }
      }
    }
    const Index hit = Index(best & 0xffffffffu);
    if (bestT > 0.f && (hit & kSurfaceHit) && !(hit & kSurfaceBack) && p.detail.steps &&
      p.detail.steps[bestTriangle] > 0)
    {
      // On a triangle with detail nodes: its grid point nearest the hit, in place of the leaf.
      const Index column = detailNearestColumn(p.detail, bestTriangle, p.triangles[bestTriangle], bestU, bestV, false,
        p.leafCount);
      best = (best & ~std::uint64_t(0xffffffffu)) | column | kSurfaceHit;
    }
    else if (bestT > 0.f && p.receivers && (hit & kSurfaceHit) && !(hit & kSurfaceBack))
    {
      const NodeBounds& s = p.nodes[hit & kSourceMask];
      const Vec3f facing = dot(s.normal, dir) < 0.f ? s.normal : -s.normal;
      const auto trace = [&p](const Ray& ray) {
        Hit h;
        bvh::traverse<false>(p.bvh, ray, h);
        return h;
      };
      const float offset = p.receivers[hit & kSourceMask].offset;
      if (hitInGap(p.faceNormals, origin + dir * bestT, s.position, facing, bestT, offset, trace))
      {
        best |= std::uint64_t(kSurfaceBack);
      }
    }
    keys[b] = best;
  }
  __syncthreads();
  // Weights: solid angle x cosine at the bin's centre, the hemisphere summed in bin order
  // (as on the CPU) and scaled to pi.
  for (int b = threadIdx.x; b < binCount; b += blockDim.x)
  {
    const float c = dot(bins.normal, p.binCenters[b]);
    binWeights[b] = c > 0.f ? p.binSolidAngles[b] * c : 0.f;
  }
  __syncthreads();
  if (threadIdx.x == 0)
  {
    float sum = 0.f;
    for (int b = 0; b < binCount; ++b)
    {
      if (dot(bins.normal, p.binCenters[b]) > 0.f)
      {
        sum += binWeights[b];
      }
    }
    hemisphere = sum;
  }
  __syncthreads();
  const float scale = hemisphere > 0.f ? kPi / hemisphere : 0.f;
  // The transport row: occupied bins whose source faces the leaf.
  for (int b = threadIdx.x; b < padded; b += blockDim.x)
  {
    std::uint64_t key = kEmptyBin;
    if (b < binCount && dot(bins.normal, p.binCenters[b]) > 0.f)
    {
      if (keys[b] == kEmptyBin)
      {
        atomicAdd(&empty, 1u);
      }
      else
      {
        atomicAdd(&occupied, 1u);
        const Index src = Index(keys[b] & 0xffffffffu);
        // A surface hit shows the side it was met on (its column may be a detail node's);
        // otherwise the side the disc faces.
        const bool front = (src & kSurfaceHit)
          ? !(src & kSurfaceBack)
          : dot(p.nodes[src].normal, bins.at - p.nodes[src].position) > 0.f;
        if (front)
        {
          key = (std::uint64_t(src & kSourceMask) << 32) | std::uint32_t(b);
        }
      }
    }
    sortKeys[b] = key;
  }
  __syncthreads();
  const std::size_t at = std::size_t(leaf) * stride;
  const Index transport = writeRow(sortKeys, padded, binWeights, scale, columns + at, weights + at);
  // The environment row: the empty bins of the hemisphere, by texel.
  for (int b = threadIdx.x; b < padded; b += blockDim.x)
  {
    sortKeys[b] = b < binCount && keys[b] == kEmptyBin && dot(bins.normal, p.binCenters[b]) > 0.f
      ? (std::uint64_t(p.binTexels[b]) << 32) | std::uint32_t(b)
      : kEmptyBin;
  }
  __syncthreads();
  const Index environment = writeRow(sortKeys, padded, binWeights, scale, envColumns + at, envWeights + at);
  if (threadIdx.x == 0)
  {
    atomicAdd(&totals[0], (unsigned long long)occupied);
    atomicAdd(&totals[1], (unsigned long long)empty);
    rowStarts[leaf] = at;
    counts[leaf] = transport;
    envCounts[leaf] = environment;
    atomicAdd(&totals[2], (unsigned long long)transport);
    atomicAdd(&totals[3], (unsigned long long)environment);
  }
}

__global__ void leafRadianceKernel(const Vec3f* albedo, const Vec3f* emission, const Rgba* fixed, const Rgba* indirect,
  std::size_t leaves, Rgba* radiance)
{
  const std::size_t e = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (e < leaves)
  {
    radiance[e] = toRgba(outgoingRadiance(albedo[e], toVec(fixed[e]), toVec(indirect[e]), emission ? emission[e] : Vec3f(0.f)));
  }
}

__global__ void pullUpKernel(TreeLevels t, Index first, Index count, Rgba* radiance)
{
  const Index k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k >= count)
  {
    return;
  }
  const Index id = t.levelNodes[first + k], i = id - t.leafCount;
  const Index l = t.left[i], r = t.right[i];
  radiance[id] = toRgba(t.area[id] > 0.f
      ? (toVec(radiance[l]) * t.area[l] + toVec(radiance[r]) * t.area[r]) / t.area[id]
      : Vec3f(0.f));
}

__global__ void addDirectKernel(const Vec3f* direct, const Rgba* environment, std::size_t count, Rgba* fixed)
{
  const std::size_t e = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (e < count)
  {
    fixed[e] = toRgba(direct[e] + toVec(environment[e]));
  }
}

__global__ void addToKernel(const Rgba* x, std::size_t count, Rgba* y)
{
  const std::size_t e = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (e < count)
  {
    y[e] = toRgba(toVec(y[e]) + toVec(x[e]));
  }
}
}

void visitPairs(const PairRules& rules, const NodePair* frontier, std::size_t count, PairList next, PairList links,
  cudaStream_t stream)
{
  if (count)
  {
    visitKernel<<<gridBlocks(count), kThreads, 0, stream>>>(rules, frontier, count, next, links);
    LINKGI_CUDA_CHECK_LAUNCH("visitKernel");
  }
}

void keepShortestPerBin(const NodePair* links, std::size_t linkCount, const NodeBounds* nodes, const float* extents,
  std::size_t nodeCount, int binsPerSide, NodeRows& rows, cudaStream_t stream)
{
  const int binCount = 6 * binsPerSide * binsPerSide;
  rows.best.resize(nodeCount * binCount);
  LINKGI_CUDA_CHECK(cudaMemsetAsync(rows.best.data(), 0xff, rows.best.size() * sizeof(std::uint64_t), stream));
  rows.zeroCounts.resize(nodeCount);
  rows.zeroCounts.fillZero(stream);
  rows.zeroCount.resize(1);
  rows.zeroCount.fillZero(stream);
  rows.zero.resize(std::max<std::size_t>(linkCount, 1));
  if (linkCount)
  {
    // CubeBins::meanSolidAngle's square root, as the CPU takes it.
    const float binAngle = std::sqrt(4.f * kPi / float(binCount));
    binKernel<<<gridBlocks(linkCount), kThreads, 0, stream>>>(links, linkCount, nodes, extents, binsPerSide, binCount,
      binAngle, rows.best.data(), rows.zeroCounts.data(), rows.zero.data(), rows.zeroCount.data());
    LINKGI_CUDA_CHECK_LAUNCH("binKernel");
  }
  rows.binCounts.resize(nodeCount);
  rows.rowCounts.resize(nodeCount);
  countRowsKernel<<<gridBlocks(nodeCount), kThreads, 0, stream>>>(rows.best.data(), nodeCount, binCount,
    rows.zeroCounts.data(), rows.binCounts.data(), rows.rowCounts.data());
  LINKGI_CUDA_CHECK_LAUNCH("countRowsKernel");
  rows.rowStarts.resize(nodeCount);
  cuda::exclusiveSum(rows.rowCounts.data(), rows.rowStarts.data(), nodeCount, rows.temp, stream);
  // Room for every link: at most all of them survive.
  rows.columns.resize(std::max<std::size_t>(linkCount, 1));
  rows.cursor.resize(nodeCount);
  writeRowsKernel<<<gridBlocks(nodeCount), kThreads, 0, stream>>>(rows.best.data(), nodeCount, binCount,
    rows.rowStarts.data(), rows.binCounts.data(), rows.columns.data(), rows.cursor.data());
  LINKGI_CUDA_CHECK_LAUNCH("writeRowsKernel");
  if (linkCount)
  {
    writeZeroKernel<<<gridBlocks(linkCount), kThreads, 0, stream>>>(rows.zero.data(), rows.zeroCount.data(),
      rows.cursor.data(), rows.columns.data());
    LINKGI_CUDA_CHECK_LAUNCH("writeZeroKernel");
  }
}

void pushToLeaves(const PushParams& p, std::size_t stride, LeafRows& rows, unsigned long long* totals,
  cudaStream_t stream)
{
  const std::size_t leaves = p.leafCount;
  rows.rowStarts.resize(leaves);
  rows.counts.resize(leaves);
  rows.envCounts.resize(leaves);
  for (auto* b : { &rows.columns, &rows.envColumns })
  {
    b->resize(std::max<std::size_t>(leaves * stride, 1));
  }
  for (auto* b : { &rows.weights, &rows.envWeights })
  {
    b->resize(std::max<std::size_t>(leaves * stride, 1));
  }
  if (!leaves)
  {
    return;
  }
  const int binCount = 6 * p.binsPerSide * p.binsPerSide;
  int padded = 1;
  while (padded < binCount)
  {
    padded <<= 1;
  }
  const std::size_t shared = (binCount + padded) * sizeof(std::uint64_t) + binCount * sizeof(float) +
    kMaxSurfaceLeaves * sizeof(Index);
  pushKernel<<<unsigned(leaves), kPushThreads, shared, stream>>>(p, stride, rows.rowStarts.data(),
    rows.counts.data(), rows.envCounts.data(), rows.columns.data(), rows.weights.data(), rows.envColumns.data(),
    rows.envWeights.data(), totals);
  LINKGI_CUDA_CHECK_LAUNCH("pushKernel");
}

void leafRadianceAndPullUp(const TreeLevels& tree, const std::vector<Index>& levelOffsets, const Vec3f* albedo,
  const Vec3f* emission, const Rgba* fixedIrradiance, const Rgba* indirect, Rgba* radiance, cudaStream_t stream)
{
  leafRadianceKernel<<<gridBlocks(tree.leafCount), kThreads, 0, stream>>>(albedo, emission, fixedIrradiance, indirect,
    tree.leafCount, radiance);
  LINKGI_CUDA_CHECK_LAUNCH("leafRadianceKernel");
  for (std::size_t l = 0; l + 1 < levelOffsets.size(); ++l)
  {
    const Index count = levelOffsets[l + 1] - levelOffsets[l];
    pullUpKernel<<<gridBlocks(count), kThreads, 0, stream>>>(tree, levelOffsets[l], count, radiance);
    LINKGI_CUDA_CHECK_LAUNCH("pullUpKernel");
  }
}

void addDirect(const Vec3f* direct, const Rgba* environment, std::size_t count, Rgba* fixed, cudaStream_t stream)
{
  if (count)
  {
    addDirectKernel<<<gridBlocks(count), kThreads, 0, stream>>>(direct, environment, count, fixed);
    LINKGI_CUDA_CHECK_LAUNCH("addDirectKernel");
  }
}

void addTo(const Rgba* x, std::size_t count, Rgba* y, cudaStream_t stream)
{
  if (count)
  {
    addToKernel<<<gridBlocks(count), kThreads, 0, stream>>>(x, count, y);
    LINKGI_CUDA_CHECK_LAUNCH("addToKernel");
  }
}
}
