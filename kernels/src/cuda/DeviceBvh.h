// The BVH on one GPU, built there into the node layout of linkgi/Bvh.h: triangles in Morton
// order, then PLOC's agglomerative clustering (default) or Karras' linear hierarchy with
// bottom-up bounds (LINKGI_CUDA_BVH=linear); refit reuses the hierarchy.
#pragma once

#include "cuda/GPUBuffer.h"

#include "shared/BvhBuild.h"
#include "shared/RayTracer.h"

#include <memory>

namespace linkgi::cuda
{
class DeviceBvh
{
public:
  /// positions / triangles are device arrays; they may change or go away after the call.
  void build(const Vec3f* positions, Index vertexCount, const Triangle* triangles,
    Index triangleCount, cudaStream_t stream);
  /// Takes the hierarchy of a tree built on the host (e.g. HostBvh::buildSah); the boxes are
  /// computed here from `positions`, as a refit does.
  void upload(const HostBvh& tree, const Vec3f* positions, const Triangle* triangles,
    cudaStream_t stream);
  /// Same triangles as the last build, moved positions: new boxes, same tree.
  void refit(const Vec3f* positions, const Triangle* triangles, cudaStream_t stream);
  /// Surface-area cost of the tree: the summed box areas of all children over the root
  /// box's area (what a ray pays in box tests, roughly). Deterministic; synchronizes.
  double cost(cudaStream_t stream);
  BvhView view() const;
  std::size_t bytes() const;
  Index triangleCount() const { return count; }

private:
  void gatherAndBound(const Vec3f* positions, const Triangle* triangles, cudaStream_t stream);
  /// PLOC on `triangles`, gathered in Morton order: hierarchy and boxes (DeviceBvhPloc.cu).
  void cluster(cudaStream_t stream);
  /// Renumbers nodes and leaves depth-first (subtrees contiguous in memory).
  void reorderDepthFirst(cudaStream_t stream);

  Index count = 0;
  GPUBuffer<BvhNode> nodes;
  GPUBuffer<BvhTriangle> triangles;
  GPUBuffer<int> leafParents;
  GPUBuffer<unsigned> arrivals;
  GPUBuffer<Index> order; ///< original triangle of each leaf
  GPUBuffer<bvh::Box> boxes;
  GPUBuffer<double> areas;
  GPUBuffer<unsigned char> temp;
  GPUBuffer<std::uint64_t> keys, sortedKeys; ///< build scratch, kept for the next build
  GPUBuffer<Index> ids;
  GPUBuffer<int> clusters[2], nearest; ///< PLOC scratch: clusters of this and the next round
  GPUBuffer<bvh::Box> clusterBoxes[2];
  GPUBuffer<std::uint64_t> flags, scanned;
  GPUBuffer<int> roundCounts; ///< PLOC: clusters left after each round of a batch
  GPUBuffer<BvhNode> reordered; ///< depth-first reordering's targets, swapped in
  GPUBuffer<int> reorderedLeafParents;
  GPUBuffer<Index> reorderedOrder;
  GPUBuffer<BvhTriangle> reorderedTriangles;
};

/// The RayTracer interface over `bvh`, which a backend builds and keeps on GPU `device`:
/// trace() and occluded() copy the rays there and the results back on `stream`, after the
/// work queued on it; build() and refit() throw. For checks of a result (the back-lit check
/// of Solver). `bvh` must outlive it.
std::unique_ptr<RayTracer> traceThrough(const DeviceBvh& bvh, int device, cudaStream_t stream);
}
