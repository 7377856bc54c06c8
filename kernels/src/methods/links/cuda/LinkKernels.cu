// Link generation on the GPU: one thread per ray, consecutive threads shooting consecutive
// directions of one element (a warp = two coherent 4x4 blocks, as in the paper), then a
// per-element merge of equal columns in shared memory (block radix sort by (row, column)).
#include "cuda/Kernels.h"

#include "methods/links/Links.h"
#include "shared/Sampling.h"

#include <cub/block/block_radix_sort.cuh>
#include <cub/block/block_scan.cuh>

#include <algorithm>

namespace linkgi::cuda
{
namespace
{
constexpr int kThreads = 256;

__device__ inline Frame elementFrame(const LinkTraceParams& p, Index x)
{
  const Index v = x < p.vertexCount ? x : x - p.vertexCount;
  const float sign = x < p.vertexCount ? 1.f : -1.f;
  return vertexFrame(p.normals[v] * sign, p.twist, p.seed, x);
}

/// Six blocks per SM: at most 40 registers (47 unbounded) with 12 bytes spilled; conference's
/// link rays measured 9.9 ms instead of 10.8 on an H200 (eight blocks spilled more and lost).
__global__ void __launch_bounds__(kThreads, 6) traceLinksKernel(LinkTraceParams p, LinkHit* hits)
{
  const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  if (i >= std::size_t(p.elementCount) * p.raysPerVertex)
  {
    return;
  }
  const Index x = p.firstElement + Index(i / p.raysPerVertex);
  const Index k = Index(i % p.raysPerVertex);
  const Index v = x < p.vertexCount ? x : x - p.vertexCount;
  const Vec3f normal = p.normals[v] * (x < p.vertexCount ? 1.f : -1.f);
  const Frame frame = vertexFrame(normal, p.twist, p.seed, x);
  Ray ray;
  ray.origin = elementRayOrigin(p.positions[v], normal, p.origins[v]);
  ray.direction = frame.toWorld(p.directions[k]);
  Hit h;
  bvh::traverse<false>(p.bvh, ray, h);
  hits[i] = LinkHit{ h.triangle, h.u, h.v };
}

/// Items per thread: 3 links per ray, R rays per thread; keys of 32 bits where they fit
/// (conference: 18 bits), which halves the sort's shared-memory traffic.
template <int R, typename Key>
struct Compress
{
  static constexpr int kItems = 3 * R;
  using Sort = cub::BlockRadixSort<Key, kThreads, kItems, float>;
  using Scan = cub::BlockScan<int, kThreads>;
  static constexpr int kTotal = kThreads * kItems;
  struct Sorted
  {
    Key keys[kTotal];
    float values[kTotal];
  };
  union Shared
  {
    typename Sort::TempStorage sort;
    Sorted sorted;
  };
};


/// Sort keys: (local row, environment?, column) packed into the fewest bits, since the block
/// sort's passes grow with the key width: column in bits [0, columnBits), then the
/// environment flag, then the row.
struct KeyLayout
{
  int columnBits;
  int endBit;
  template <typename Key>
  __device__ Key key(int row, bool env, Index column) const
  {
    return (static_cast<Key>(row) << (columnBits + 1)) | (static_cast<Key>(env) << columnBits) | column;
  }
  /// Segment = (row, environment?) = key >> columnBits.
  template <typename Key>
  __device__ int segment(Key key) const { return int(key >> columnBits); }
  template <typename Key>
  __device__ Index column(Key key) const
  {
    return Index(key & ((Key(1) << columnBits) - 1));
  }
};

/// One block merges the links of `rowsPerBlock` elements (R = 1: n_C <= 256 rays per
/// element, one ray per thread; R = 4: one element of up to 1024 rays, rays t*4..t*4+3 in
/// thread t). Keys are (local row, environment?, column); the stable sort keeps equal keys
/// in ray order, so weights add up in the CPU's order.
template <int R, typename Key>
__global__ void __launch_bounds__(kThreads) compressKernel(LinkCompressParams p,
  const LinkHit* hits, LinkRowsOut out, int rowsPerBlock, KeyLayout layout)
{
  using C = Compress<R, Key>;
  constexpr Key kNoKey = ~Key(0);
  __shared__ typename C::Shared shared;
  __shared__ typename C::Scan::TempStorage scanStorage;
  __shared__ int segmentStart[2 * kThreads];
  __shared__ int segmentCount[2 * kThreads];
  const LinkTraceParams& t = p.trace;
  const Index n = t.raysPerVertex;
  const Index firstRow = blockIdx.x * rowsPerBlock; // within the batch
  for (int s = threadIdx.x; s < 2 * rowsPerBlock; s += kThreads)
  {
    segmentCount[s] = 0;
  }

  LinkParams lp;
  lp.vertexCount = t.vertexCount;
  lp.twoSided = p.twoSided;
  lp.weight = kPi / float(n);
  lp.envWidth = p.envWidth;
  lp.envHeight = p.envHeight;
  lp.detail = p.detail;

  Key keys[C::kItems];
  float values[C::kItems];
  int raw = 0;
  for (int r = 0; r < R; ++r)
  {
    const int localRow = R == 1 ? int(threadIdx.x / n) : 0;
    const Index k = R == 1 ? threadIdx.x % n : threadIdx.x * R + r;
    const Index row = firstRow + localRow;
    RayLinks links;
    if (localRow < rowsPerBlock && row < t.elementCount && k < n)
    {
      const Index x = t.firstElement + row;
      const Vec3f dir = elementFrame(t, x).toWorld(t.directions[k]);
      const LinkHit lh = hits[std::size_t(row) * n + k];
      Hit h;
      h.triangle = lh.triangle;
      h.u = lh.u;
      h.v = lh.v;
      links = linksOfRay(h, dir, p.triangles, p.faceNormals, lp);
    }
    raw += links.count;
    for (int j = 0; j < 3; ++j)
    {
      const bool valid = j < links.count;
      keys[3 * r + j] = valid ? layout.key<Key>(localRow, links.environment, links.column[j]) : kNoKey;
      values[3 * r + j] = valid ? links.weight[j] : 0.f;
    }
  }
  for (int offset = 16; offset > 0; offset /= 2)
  {
    raw += __shfl_down_sync(0xffffffffu, raw, offset);
  }
  if ((threadIdx.x & 31) == 0 && raw)
  {
    atomicAdd(out.rawLinks, static_cast<unsigned long long>(raw));
  }

  typename C::Sort(shared.sort).Sort(keys, values, 0, layout.endBit);
  __syncthreads(); // the sort's storage becomes the sorted arrays
  for (int i = 0; i < C::kItems; ++i)
  {
    shared.sorted.keys[threadIdx.x * C::kItems + i] = keys[i];
    shared.sorted.values[threadIdx.x * C::kItems + i] = values[i];
  }
  __syncthreads();

  // A head starts a run of equal keys; heads are numbered in order by a block scan.
  const Key mask = layout.endBit >= int(8 * sizeof(Key)) ? kNoKey : Key((Key(1) << layout.endBit) - 1);
  const auto keyAt = [&](int i) { return shared.sorted.keys[i] & mask; };
  int heads = 0;
  for (int i = 0; i < C::kItems; ++i)
  {
    const int at = threadIdx.x * C::kItems + i;
    heads += keyAt(at) != (kNoKey & mask) && (at == 0 || keyAt(at) != keyAt(at - 1));
  }
  int headIndex = 0;
  typename C::Scan(scanStorage).ExclusiveSum(heads, headIndex);
  // Segment = (local row, environment?); its first head's number gives offsets in the row.
  for (int i = 0; i < C::kItems; ++i)
  {
    const int at = threadIdx.x * C::kItems + i;
    const Key key = keyAt(at);
    if (key == (kNoKey & mask) || (at > 0 && key == keyAt(at - 1)))
    {
      continue;
    }
    const int segment = layout.segment(key);
    if (at == 0 || layout.segment(Key(keyAt(at - 1))) != segment)
    {
      segmentStart[segment] = headIndex;
    }
    atomicAdd(&segmentCount[segment], 1);
    ++headIndex;
  }
  __syncthreads();
  headIndex -= heads; // back to this thread's first head
  for (int i = 0; i < C::kItems; ++i)
  {
    const int at = threadIdx.x * C::kItems + i;
    const Key key = keyAt(at);
    if (key == (kNoKey & mask) || (at > 0 && key == keyAt(at - 1)))
    {
      continue;
    }
    float sum = 0.f;
    for (int j = at; j < C::kTotal && keyAt(j) == key; ++j)
    {
      sum += shared.sorted.values[j];
    }
    const int segment = layout.segment(key);
    const bool env = segment & 1;
    const Index row = firstRow + (segment >> 1);
    const std::size_t slot = std::size_t(row) * (env ? n : 3 * n) + (headIndex - segmentStart[segment]);
    (env ? out.envColumns : out.columns)[slot] = layout.column(key);
    (env ? out.envWeights : out.weights)[slot] = sum;
    ++headIndex;
  }
  for (int s = threadIdx.x; s < rowsPerBlock; s += kThreads)
  {
    if (firstRow + s < t.elementCount)
    {
      out.counts[firstRow + s] = segmentCount[2 * s];
      out.envCounts[firstRow + s] = segmentCount[2 * s + 1];
    }
  }
}

__global__ void packRowsKernel(const Index* srcColumns, const float* srcWeights, Index capacity,
  const Index* counts, const Offset* offsets, Index rows, PackedRows dst)
{
  // One warp per row.
  const Index row = Index((std::size_t(blockIdx.x) * blockDim.x + threadIdx.x) / 32);
  const int lane = threadIdx.x & 31;
  if (row >= rows)
  {
    return;
  }
  const std::size_t src = std::size_t(row) * capacity;
  const Offset at = offsets[row];
  const Index count = counts[row];
  for (Index i = lane; i < count; i += 32)
  {
    dst.columns[at + i] = srcColumns[src + i];
    dst.weights[at + i] = srcWeights[src + i];
  }
  if (lane == 0)
  {
    dst.rowStarts[row] = at;
    dst.rowCounts[row] = count;
  }
}

/// Number of bits that hold x (and so every value below it): 0 for 0, 1 for 1, 2 for 2..3.
int bitsFor(unsigned x)
{
  int b = 0;
  while (b < 32 && (std::uint64_t(1) << b) <= x)
  {
    ++b;
  }
  return b;
}
}

void traceLinks(const LinkTraceParams& p, LinkHit* hits, cudaStream_t stream)
{
  const std::size_t rays = std::size_t(p.elementCount) * p.raysPerVertex;
  if (rays)
  {
    traceLinksKernel<<<unsigned((rays + kThreads - 1) / kThreads), kThreads, 0, stream>>>(p, hits);
    LINKGI_CUDA_CHECK_LAUNCH("traceLinksKernel");
  }
}

bool compressLinks(const LinkCompressParams& p, const LinkHit* hits, const LinkRowsOut& out,
  cudaStream_t stream)
{
  const Index n = p.trace.raysPerVertex, rows = p.trace.elementCount;
  if (n == 0 || n > kMaxCompressRays)
  {
    return false;
  }
  if (rows == 0)
  {
    return true;
  }
  // Columns are elements (< 2 x vertices) and detail nodes, or environment texels.
  const Index elements = (p.twoSided ? 2 * p.trace.vertexCount : p.trace.vertexCount) +
    p.detail.nodesPerSide * (p.twoSided ? 2 : 1);
  const unsigned texels = p.envWidth > 0 ? unsigned(p.envWidth) * unsigned(p.envHeight) : 1u;
  KeyLayout layout;
  layout.columnBits = bitsFor(std::max(unsigned(elements), texels));
  // 32-bit keys need one bit to spare: the all-ones key marks an empty slot.
  if (n <= kThreads)
  {
    const int rowsPerBlock = int(kThreads / n);
    layout.endBit = layout.columnBits + 1 + bitsFor(unsigned(rowsPerBlock - 1));
    const unsigned blocks = unsigned((rows + rowsPerBlock - 1) / rowsPerBlock);
    if (layout.endBit < 32)
      compressKernel<1, unsigned><<<blocks, kThreads, 0, stream>>>(p, hits, out, rowsPerBlock, layout);
    else
      compressKernel<1, unsigned long long><<<blocks, kThreads, 0, stream>>>(p, hits, out, rowsPerBlock, layout);
    LINKGI_CUDA_CHECK_LAUNCH("compressKernel<1>");
  }
  else
  {
    layout.endBit = layout.columnBits + 1;
    if (layout.endBit < 32)
      compressKernel<4, unsigned><<<rows, kThreads, 0, stream>>>(p, hits, out, 1, layout);
    else
      compressKernel<4, unsigned long long><<<rows, kThreads, 0, stream>>>(p, hits, out, 1, layout);
    LINKGI_CUDA_CHECK_LAUNCH("compressKernel<4>");
  }
  return true;
}

void packRows(const Index* srcColumns, const float* srcWeights, Index capacity, const Index* counts,
  const Offset* offsets, Index rows, const PackedRows& dst, cudaStream_t stream)
{
  if (rows)
  {
    const std::size_t threads = std::size_t(rows) * 32;
    packRowsKernel<<<unsigned((threads + kThreads - 1) / kThreads), kThreads, 0, stream>>>(
      srcColumns, srcWeights, capacity, counts, offsets, rows, dst);
    LINKGI_CUDA_CHECK_LAUNCH("packRowsKernel");
  }
}
}
