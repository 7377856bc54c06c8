// Implicit-visibility links (Dong, Kautz, Theobalt & Seidel 2007): links between the nodes
// of a ClusterTree, binned by direction in a world-aligned cube map of 6 x N x N bins; the
// shortest link per bin wins, so visibility is implied and no ray is traced.
#pragma once

#include "methods/iv/ClusterTree.h"
#include "methods/iv/IvShared.h"

#include "shared/Bounce.h"
#include "shared/DetailNodes.h"
#include "shared/RayOrigin.h"
#include "shared/RayTracer.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace linkgi::iv
{
/// The cube face of a nonzero direction d (+x, -x, +y, -y, +z, -z) and its coordinates
/// on it, u and v in [-1, 1] (a NaN for d = 0).
LINKGI_HOST_DEVICE inline int cubeFace(const Vec3f& d, float& u, float& v)
{
  const float ax = std::abs(d.x), ay = std::abs(d.y), az = std::abs(d.z);
  if (ax >= ay && ax >= az)
  {
    u = d.y / ax;
    v = d.z / ax;
    return d.x > 0.f ? 0 : 1;
  }
  if (ay >= az)
  {
    u = d.x / ay;
    v = d.z / ay;
    return d.y > 0.f ? 2 : 3;
  }
  u = d.x / az;
  v = d.y / az;
  return d.z > 0.f ? 4 : 5;
}

/// The column or row (0 to n - 1) of a cube-face coordinate in [-1, 1]. Clamped by
/// comparisons (a NaN gives 0), not fminf/fmaxf: on the host those are libm calls, and
/// this runs for every link.
LINKGI_HOST_DEVICE inline int cubeCell(float u, int n)
{
  const float last = float(n - 1);
  const float x = (u + 1.f) * 0.5f * n;
  return static_cast<int>(x > 0.f ? (x < last ? x : last) : 0.f);
}

/// The cube-map bin (face * N * N + row * N + column) of a nonzero direction d.
LINKGI_HOST_DEVICE inline int cubeBin(const Vec3f& d, int n)
{
  float u, v;
  const int face = cubeFace(d, u, v);
  return (face * n + cubeCell(v, n)) * n + cubeCell(u, n);
}

/// Each vertex's adjacent triangles (CSR): the surface of its element, which a leaf near
/// the receiver is drawn from (IvShared.h leafReach).
struct ElementTriangles
{
  std::vector<Index> offsets;   ///< vertexCount + 1
  std::vector<Index> triangles; ///< ids into Scene::triangles
  static ElementTriangles of(const Scene& scene);
};

/// The 6 N^2 bins: unit centre directions and exact solid angles (they sum to 4 pi; a
/// corner bin is about a fifth of a centre bin).
struct CubeBins
{
  int n = 0;
  std::vector<Vec3f> center;
  std::vector<float> solidAngle;
  static CubeBins make(int n);
  std::size_t count() const { return center.size(); }
  /// 4 pi / (6 N^2): the subdivision threshold.
  float meanSolidAngle() const { return 4.f * kPi / float(count()); }
};

struct LinkCreationOptions
{
  /// Heights above a receiver's plane below this count as on it (coplanar discs never
  /// exchange light): a small fraction of the scene size.
  float planeEpsilon = 0.f;
  /// Clusters whose normals spread by more than this half angle (radians) are subdivided
  /// before they are linked, so that which side a source shows is decided per narrow cone.
  float maxConeAngle = 0.785398f;

  /// The options for `scene`: the plane epsilon a tenth of its ray epsilon.
  static LinkCreationOptions of(const Scene& scene);
};

/// Links as created between tree nodes, before refinement: row = receiving node, columns
/// = source nodes. A pair of nodes is linked once both see the other within a bin's solid
/// angle (else the larger is subdivided) and each end that can face the other receives;
/// then each receiving node's bins (seen from its centre) keep only their shortest link.
struct NodeLinks
{
  SparseMatrix byReceiver; ///< weights unused (empty)
  std::uint64_t pairsVisited = 0;
  std::uint64_t created = 0; ///< links gathered for the final pass in which each node's bins keep their shortest (each task has already kept its own shortest)
};

/// The pair recursion's record of every node (positions, bounds, first child).
std::vector<NodeBounds> nodeBounds(const ClusterTree& tree);
/// The pair recursion's rules over a tree: `nodes`, `left`, `right`, `extents`,
/// `extentSlabs` (ClusterTree's, or their copies on a GPU) and the thresholds of `bins` and
/// `options`.
PairRules pairRules(const NodeBounds* nodes, const Index* left, const Index* right, const float* extents,
  const float* extentSlabs, std::size_t leafCount, const CubeBins& bins, const LinkCreationOptions& options);

/// `rows` (per leaf, or null for all): only the links that reach these leaves' ancestors
/// (a process's share under MPI, or a sample's); pairs of which neither holds such a leaf
/// are not followed. `createdPerReceiver` (if not null): per node, the links gathered for
/// the final pass that receives it (NodeLinks::created, row by row).
NodeLinks createNodeLinks(const ClusterTree& tree, const CubeBins& bins,
  const LinkCreationOptions& options, const ProgressCallback& progress = {}, const std::uint8_t* rows = nullptr,
  std::vector<Index>* createdPerReceiver = nullptr);

/// What the leaves gather after refinement and push-down.
struct LeafLinks
{
  /// Row = leaf (vertex), column = source node, weight = the bin's cosine-weighted solid
  /// angle. Sources that show the leaf their back occupy their bin but are not listed
  /// (they are black, as a ray hitting a back face sees black in the link method).
  SparseMatrix transport;
  /// Row = leaf, column = environment texel (environmentTexelRadiance's layout): the bins
  /// of the leaf's hemisphere that no link occupies.
  SparseMatrix environment;
  std::uint64_t occupiedBins = 0, emptyBins = 0;
  /// The leaves' entries, transport and environment.
  std::uint64_t entries() const { return transport.nonZeros() + environment.nonZeros(); }
};

/// Refinement and push-down in one pass: for each leaf, the links of every node on its path
/// to the root compete per bin, as seen from the leaf (direction and distance from its
/// disc to the source), and the shortest wins. This is what the paper's top-down
/// refinement (a shorter link further down removes a parent's link in its bin, a longer
/// one is removed) followed by pushing every receiving end to the leaves leaves at a leaf.
/// Leaves wider than a bin are splatted as discs, or, where a disc would misplace their
/// surface (near, or seen from behind), drawn from their triangles of `scene` (`elements`)
/// into every bin whose centre ray meets them; a back so met occupies its bin and gives
/// black. Bins of the leaf's hemisphere are weighted by solid angle x cosine at their
/// centre, scaled so that the whole hemisphere weighs pi (a closed surface gathers
/// exactly); empty bins see `scene`'s environment. `receivers` (per leaf, or empty): where
/// a leaf looks from, relative to its vertex (the ray-origin shift towards its one-ring, so
/// a vertex on a contact line looks from inside the room; its surface rays also leave from
/// the origin's offset along the normal, as link rays do).
/// `tracer` (over `scene`, or null): a bin whose surface hit lies in a gap that its leaf's
/// vertex is not in (hitInGap: the floor under an object resting on it, read from the lit
/// floor beside it) gives black, as a back; it needs `receivers`' offsets. A front surface
/// hit on a triangle with `detail` nodes goes to the grid point nearest it (columns after
/// the tree's nodes, DetailNodes::grid(tree.nodeCount())) and is not tested for a gap.
/// `rows` (per leaf, or null for all): the leaves to push to; the others get empty rows
/// (a process's share under MPI, SolverOptions::partition).
LeafLinks pushToLeaves(const ClusterTree& tree, const NodeLinks& links, const CubeBins& bins,
  const Scene& scene, const std::vector<Vec3f>& faceNormals, const ElementTriangles& elements,
  const std::vector<RayOrigin>& receivers, const RayTracer* tracer, const DetailNodes& detail,
  const ProgressCallback& progress = {}, const std::uint8_t* rows = nullptr);

/// (Each function reports its own fraction in [0, 1] through `progress`.)
/// n_B gather iterations: L at the leaves, pulled up the tree (area-weighted), gathered at
/// the leaves through `transport`; as iterateBounces, from E_ind = 0, returns E_ind.
/// `inputs.extraColumns` follow the tree's nodes (detail nodes), written from the leaves'
/// radiance by `inputs.extraRadiance`.
/// With `exchange` (a partition's), `transport` holds this process's rows only and each
/// gather is completed by the other processes' rows before the next bounce pulls it up.
std::vector<Vec3f> iterateHierarchicalBounces(const ClusterTree& tree,
  const SparseMatrix& transport, const BounceInputs& inputs, std::uint32_t bounces,
  const ProgressCallback& progress = {}, const std::function<void(std::vector<Vec3f>&)>& exchange = {});
}
