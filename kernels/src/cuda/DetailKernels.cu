#include "cuda/DetailKernels.h"

namespace linkgi::cuda
{
namespace
{
constexpr int kThreads = 256;

__global__ void detailDirectKernel(DetailParams p, const Light* lights, Index lightCount, Vec3f* out,
  unsigned long long* rays)
{
  const Index k = blockIdx.x * blockDim.x + threadIdx.x;
  unsigned traced = 0;
  if (k < p.nodeCount * p.sides)
  {
    const auto occluded = [&p, &traced](const Ray& ray) {
      ++traced;
      Hit h;
      return bvh::traverse<true>(p.bvh, ray, h);
    };
    out[k] = detailNodeDirect(p.nodes[k % p.nodeCount], k >= p.nodeCount ? 1 : 0, p.triangles,
      p.positions, p.normals, p.faceNormals, p.origins, lights, lightCount, occluded);
  }
  for (int offset = 16; offset > 0; offset /= 2)
  {
    traced += __shfl_down_sync(0xffffffffu, traced, offset);
  }
  if ((threadIdx.x & 31) == 0 && traced)
  {
    atomicAdd(rays, static_cast<unsigned long long>(traced));
  }
}

__global__ void detailRadianceKernel(DetailParams p, Index elements, Index vertexCount, const Vec3f* direct,
  const Vec3f* albedo, const Vec3f* nodeDirect, Rgba* radiance)
{
  const Index k = blockIdx.x * blockDim.x + threadIdx.x;
  if (k < p.nodeCount * p.sides)
  {
    const DetailNode node = p.nodes[k % p.nodeCount];
    const auto radianceAt = [radiance](Index e) { return toVec(radiance[e]); };
    radiance[elements + k] = toRgba(detailNodeRadiance(node, p.triangles[node.triangle],
      k >= p.nodeCount ? 1 : 0, vertexCount, radianceAt, direct, albedo, nodeDirect[k]));
  }
}

unsigned blocksFor(Index count)
{
  return unsigned((std::size_t(count) + kThreads - 1) / kThreads);
}
}

void detailDirect(const DetailParams& p, const Light* lights, Index lightCount, Vec3f* nodeDirect,
  unsigned long long* rays, cudaStream_t stream)
{
  const Index count = p.nodeCount * p.sides;
  if (count)
  {
    detailDirectKernel<<<blocksFor(count), kThreads, 0, stream>>>(p, lights, lightCount, nodeDirect, rays);
    LINKGI_CUDA_CHECK_LAUNCH("detailDirectKernel");
  }
}

void detailRadiance(const DetailParams& p, Index elements, Index vertexCount, const Vec3f* direct,
  const Vec3f* albedo, const Vec3f* nodeDirect, Rgba* radiance, cudaStream_t stream)
{
  const Index count = p.nodeCount * p.sides;
  if (count)
  {
    detailRadianceKernel<<<blocksFor(count), kThreads, 0, stream>>>(p, elements, vertexCount, direct, albedo,
      nodeDirect, radiance);
    LINKGI_CUDA_CHECK_LAUNCH("detailRadianceKernel");
  }
}
}
