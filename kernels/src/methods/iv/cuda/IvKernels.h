// Launchers of the implicit-visibility method's CUDA kernels: host-callable, no __global__
// here. The per-item formulas are iv/IvShared.h's (and cubeBin's), the same the CPU runs.
#pragma once

#include "methods/iv/IvShared.h"

#include "cuda/GPUBuffer.h"
#include "cuda/Kernels.h"

#include <vector>

namespace linkgi::iv::gpu
{
struct NodePair
{
  Index a, b;
};

/// Appends into `out` while there is room; `count` counts every append, so a count above
/// `capacity` says how much room the step needed.
struct PairList
{
  NodePair* out = nullptr;
  unsigned long long* count = nullptr;
  unsigned long long capacity = 0;
};

/// One level of the pair recursion: every pair of `frontier` is linked (into `links`, as
/// (receiver, source)), pruned, or subdivided (into `next`). `rules` holds device pointers.
void visitPairs(const PairRules& rules, const NodePair* frontier, std::size_t count, PairList next,
  PairList links, cudaStream_t stream);

/// The node links, each receiving node's bins keeping their shortest link (the paper's rule
/// at creation), as rows: `best` (nodes x bins keys, filled here) and the rows' starts,
/// counts and sources. `zero` (room for `linkCount` pairs) takes the links of no direction
/// (two nodes at one place), which are kept. Returns nothing; `rowStarts`, `rowCounts` and
/// `columns` are resized by the caller from `linkCount` and the node count.
struct NodeRows
{
  cuda::GPUBuffer<std::uint64_t> best;
  cuda::GPUBuffer<Index> zeroCounts, binCounts, rowCounts, columns;
  cuda::GPUBuffer<Offset> rowStarts, cursor;
  cuda::GPUBuffer<NodePair> zero;
  cuda::GPUBuffer<unsigned long long> zeroCount;
  cuda::GPUBuffer<unsigned char> temp;
};
void keepShortestPerBin(const NodePair* links, std::size_t linkCount, const NodeBounds* nodes, const float* extents,
  std::size_t nodeCount, int binsPerSide, NodeRows& rows, cudaStream_t stream);

/// What the push to the leaves reads.
struct PushParams
{
  const NodeBounds* nodes = nullptr; ///< position, radius, normal per node
  const float* extents = nullptr;    ///< per leaf: ClusterTree::extent
  const Index* parent = nullptr;
  const Offset* rowStarts = nullptr; ///< the node links' rows
  const Index* rowCounts = nullptr;
  const Index* columns = nullptr;
  const RayOrigin* receivers = nullptr; ///< per leaf: where it looks from (its shift and offset)
  const Vec3f* positions = nullptr;     ///< the mesh, for the leaves drawn from their surface
  const Triangle* triangles = nullptr;
  const Vec3f* faceNormals = nullptr; ///< frontFaceNormals: which side of a triangle is its front
  BvhView bvh; ///< the mesh's: a surface hit in a gap its leaf is not in gives black (hitInGap)
  const Index* elementOffsets = nullptr; ///< ElementTriangles: each vertex's triangles
  const Index* elementTriangles = nullptr;
  const Vec3f* binCenters = nullptr;
  const float* binSolidAngles = nullptr;
  const Index* binTexels = nullptr; ///< the environment texel each bin's centre sees
  /// The large triangles' nodes (columns after the tree's nodes): a front surface hit on
  /// one goes to its grid point nearest the hit, and is not tested for a gap.
  DetailGrid detail;
  Index leafCount = 0;
  int binsPerSide = 0;
  float binAngle = 0.f; ///< sqrt of the mean bin solid angle
};

/// Each leaf's rows of the transport and environment matrices (ImplicitLinks.h
/// pushToLeaves), `stride` entries of room per leaf (rowStarts[leaf] = leaf * stride).
/// totals: [occupied bins, empty bins, transport entries, environment entries, overflows
/// of the leaves drawn from their surface], added to.
struct LeafRows
{
  cuda::GPUBuffer<Offset> rowStarts;
  cuda::GPUBuffer<Index> counts, envCounts, columns, envColumns;
  cuda::GPUBuffer<float> weights, envWeights;
};
void pushToLeaves(const PushParams& p, std::size_t stride, LeafRows& rows, unsigned long long* totals,
  cudaStream_t stream);
/// Bins per side the GPU's push holds in shared memory.
constexpr int kMaxBinsPerSide = 16;

/// The tree's pull-up, level by level (levelNodes: the interior nodes ordered by height,
/// level l = [levelOffsets[l], levelOffsets[l + 1]), children before parents).
struct TreeLevels
{
  const Index* left = nullptr;
  const Index* right = nullptr;
  const float* area = nullptr;
  const Index* levelNodes = nullptr;
  Index leafCount = 0;
};

/// radiance[leaf] = outgoingRadiance(albedo, fixed, indirect, emission) for the leaves, then
/// pulled up (area-weighted) through every level. emission: null without emissive surfaces.
void leafRadianceAndPullUp(const TreeLevels& tree, const std::vector<Index>& levelOffsets, const Vec3f* albedo,
  const Vec3f* emission, const cuda::Rgba* fixedIrradiance, const cuda::Rgba* indirect, cuda::Rgba* radiance,
  cudaStream_t stream);

/// fixed = direct + environment (per leaf).
void addDirect(const Vec3f* direct, const cuda::Rgba* environment, std::size_t count, cuda::Rgba* fixed,
  cudaStream_t stream);
/// y += x (per leaf).
void addTo(const cuda::Rgba* x, std::size_t count, cuda::Rgba* y, cudaStream_t stream);
}
