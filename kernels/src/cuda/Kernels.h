// Launchers of the CUDA backend's kernels: host-callable, no __global__ here. Arguments
// are device pointers and plain structs; every launcher runs on `stream` and checks its
// launch (LINKGI_CUDA_CHECK_LAUNCH). The per-item math lives in the shared headers
// (Bvh.h, BvhBuild.h, Links.h, DirectLight.h, Bounce.h) that the CPU uses too.
#pragma once

#include "cuda/CudaCheck.h"

#include "shared/Bvh.h"
#include "shared/DetailNodes.h"
#include "shared/RayOrigin.h"
#include "linkgi/Scene.h"

#include <cuda_runtime_api.h>

#include <cstdint>

namespace linkgi::cuda
{
/// RGB padded to 16 bytes, so a gathered vector element is one load.
struct alignas(16) Rgba
{
  float r, g, b, a;
};

LINKGI_HOST_DEVICE inline Vec3f toVec(const Rgba& c)
{
  return { c.r, c.g, c.b };
}
LINKGI_HOST_DEVICE inline Rgba toRgba(const Vec3f& v)
{
  return { v.x, v.y, v.z, 0.f };
}

/// One link ray's result as the link stage stores it.
struct LinkHit
{
  Index triangle; ///< kInvalidIndex on a miss
  float u, v;
};

/// Rows [firstElement, firstElement + rows) of a sparse matrix in device memory (row =
/// receiving element), CSR with each row's start and length stored apart: local row r is
/// entries [rowStarts[r], rowStarts[r] + rowCounts[r]). Entry offsets are 64-bit: one GPU's
/// rows of a large mesh hold more than 2^32 links. Each link batch is one such block, kept on
/// the GPU that linked it.
struct CsrView
{
  const Offset* rowStarts = nullptr;
  const Index* rowCounts = nullptr;
  const Index* columns = nullptr;
  const float* weights = nullptr;
  Index rows = 0;
  Index firstElement = 0;
  Offset nonZeros = 0;
  /// Threads that sum one row (8, 16 or 32), from the mean row length of the whole matrix
  /// (lanesForRows), not of this block: a row then sums in the same order however the
  /// rows are split into batches and GPUs.
  int lanes = 8;
};

/// Threads per block of the element-wise kernels, and the blocks that cover `n` items.
constexpr int kBlockThreads = 128;
inline unsigned gridBlocks(std::size_t n, int threads = kBlockThreads)
{
  return unsigned((n + std::size_t(threads) - 1) / std::size_t(threads));
}

/// The threads per row for a matrix of `rows` rows and `nonZeros` entries in all: a full
/// warp for long rows.
int lanesForRows(Offset nonZeros, std::uint64_t rows);

// ---- rays (generic, for the RayTracer interface) ----
void traceRays(const BvhView& bvh, const Ray* rays, Hit* hits, std::size_t count, cudaStream_t stream);
void occludedRays(const BvhView& bvh, const Ray* rays, std::uint8_t* occluded, std::size_t count,
  cudaStream_t stream);

// ---- link generation ----
struct LinkTraceParams
{
  BvhView bvh;
  const Vec3f* positions = nullptr;
  const Vec3f* normals = nullptr;
  const RayOrigin* origins = nullptr;
  const Vec3f* directions = nullptr; ///< raysPerVertex local directions
  Index raysPerVertex = 0;
  Index vertexCount = 0;
  bool twist = true;
  std::uint32_t seed = 0;
  Index firstElement = 0; ///< the batch: elements [firstElement, firstElement + elementCount)
  Index elementCount = 0;
};
/// hits[(x - firstElement) * raysPerVertex + k] for ray k of element x.
void traceLinks(const LinkTraceParams& p, LinkHit* hits, cudaStream_t stream);

/// Where compressLinks writes: per element a fixed-capacity row (3 n_C transport entries,
/// n_C environment entries) and the number of entries used.
struct LinkRowsOut
{
  Index* columns = nullptr;
  float* weights = nullptr;
  Index* counts = nullptr;
  Index* envColumns = nullptr;
  float* envWeights = nullptr;
  Index* envCounts = nullptr;
  unsigned long long* rawLinks = nullptr; ///< incremented by the links before merging
};
struct LinkCompressParams
{
  LinkTraceParams trace;
  const Triangle* triangles = nullptr;
  const Vec3f* faceNormals = nullptr;
  bool twoSided = false;
  int envWidth = 0, envHeight = 0;
  DetailGrid detail; ///< hits on subdivided triangles link to their nodes (Links.h)
};
/// Merges each element's links with equal columns (weights summed in ray order, columns
/// sorted); deterministic. Returns false if raysPerVertex is above kMaxCompressRays.
constexpr Index kMaxCompressRays = 1024;
bool compressLinks(const LinkCompressParams& p, const LinkHit* hits, const LinkRowsOut& out,
  cudaStream_t stream);

/// Where packRows puts a batch's rows: entries from 0 on, in row order, each row's start
/// and count at its local row.
struct PackedRows
{
  Index* columns = nullptr;
  float* weights = nullptr;
  Offset* rowStarts = nullptr;
  Index* rowCounts = nullptr;
};
/// Row r of the batch: `counts[r]` entries from src + r * capacity to dst.columns + offsets[r];
/// dst.rowStarts[r] = offsets[r], dst.rowCounts[r] = counts[r].
void packRows(const Index* srcColumns, const float* srcWeights, Index capacity, const Index* counts,
  const Offset* offsets, Index rows, const PackedRows& dst, cudaStream_t stream);

// ---- light links ----
struct DirectLightParams
{
  BvhView bvh;
  const Vec3f* positions = nullptr;
  const Vec3f* normals = nullptr;
  const RayOrigin* origins = nullptr;
  const Index* edges = nullptr; ///< pairs (a, b)
  const Index* neighbourOffsets = nullptr;
  const Index* vertexEdges = nullptr;
  Index vertexCount = 0;
  Index edgeCount = 0;
  bool oversampling = true;
};
/// Adds the shadowed irradiance of lights[0, lightCount) (device memory) on one side (sign
/// +1 front, -1 back) to irradiance[v + sideOffset], light after light. vertexVisible /
/// edgeVisible are scratch of lightCount x vertexCount / edgeCount floats; rays counts the
/// shadow rays traced. Two launches for all lights.
void addDirectLights(const DirectLightParams& p, const Light* lights, int lightCount, float sign,
  Index sideOffset, float* vertexVisible, float* edgeVisible, Vec3f* irradiance,
  unsigned long long* rays, cudaStream_t stream);

// ---- bounces, smoothing, output ----
/// y[m.firstElement + r] = (M x)[r] for the block's rows, RGB; 8..32 threads per row.
void gatherRgb(const CsrView& m, const Rgba* x, Rgba* y, cudaStream_t stream);

struct BounceParams
{
  Index elements = 0;
  Index vertexCount = 0;
  const Vec3f* direct = nullptr;   ///< E_d per element
  const Rgba* environment = nullptr; ///< E_env per element
  const Vec3f* albedo = nullptr;   ///< per vertex
  const Vec3f* emission = nullptr; ///< per vertex, nullptr = none (front sides emit)
};
/// For elements [first, first + count): radiance = L(E_ind = 0); fixedIrradiance = E_d + E_env.
void startBounces(const BounceParams& p, Index first, Index count, Rgba* fixedIrradiance,
  Rgba* radiance, cudaStream_t stream);
/// One Jacobi bounce over the block's rows, fused with the next radiance: indirect = W
/// radiance, and when `nextRadiance` is not null, nextRadiance = L(indirect). Reads the whole
/// radiance vector, writes only the block's elements.
void bounce(const CsrView& w, const BounceParams& p, const Rgba* fixedIrradiance,
  const Rgba* radiance, Rgba* indirect, Rgba* nextRadiance, cudaStream_t stream);

struct FinishParams
{
  BounceParams bounce;
  const Rgba* indirect = nullptr; ///< after the bounces, nullptr if there were none
  bool smoothing = false;
  float cosFeatureAngle = 0.f;
  const Index* neighbourOffsets = nullptr;
  const Index* neighbours = nullptr;
  const Vec3f* normals = nullptr;
};
/// Writes E_d, smoothed E_ind + E_env and L = Le + rho/pi (E_d + E_ind) per element into
/// out[0, n), out[n, 2n), out[2n, 3n).
void finish(const FinishParams& p, Vec3f* out, cudaStream_t stream);
}
