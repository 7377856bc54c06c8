// Light exchange on the GPU: a custom RGB CSR gather (one pass over the matrix for all three
// channels, 16-byte vector loads), fused with the next radiance; smoothing and the output.
#include "cuda/Kernels.h"

#include "shared/Bounce.h"

namespace linkgi::cuda
{
namespace
{
constexpr int kThreads = 256;

/// Sum over row `row` of M x with `Lanes` threads; every lane returns the full sum. All
/// lanes of the warp must call it (the shuffles name the whole warp); rows past the end
/// take part with an empty range.
template <int Lanes>
__device__ inline Vec3f gatherRow(const CsrView& m, const Rgba* __restrict__ x, Index row, int lane)
{
  const bool active = row < m.rows;
  const Offset begin = active ? __ldg(m.rowStarts + row) : 0;
  const Offset end = active ? begin + __ldg(m.rowCounts + row) : 0;
  float r = 0.f, g = 0.f, b = 0.f;
  const float4* xs = reinterpret_cast<const float4*>(x);
  Offset i = begin + lane;
  // Four entries per lane per step keep more loads in flight; the matrix streams through
  // once (evict-first loads), so the gathered vector stays in L2.
  for (; i + 3 * Lanes < end; i += 4 * Lanes)
  {
    Index c[4];
    float w[4];
#pragma unroll
    for (int k = 0; k < 4; ++k)
    {
      c[k] = __ldcs(m.columns + i + k * Lanes);
      w[k] = __ldcs(m.weights + i + k * Lanes);
    }
    float4 v[4];
#pragma unroll
    for (int k = 0; k < 4; ++k)
    {
      v[k] = __ldg(xs + c[k]);
    }
#pragma unroll
    for (int k = 0; k < 4; ++k)
    {
      r += w[k] * v[k].x;
      g += w[k] * v[k].y;
      b += w[k] * v[k].z;
    }
  }
  for (; i < end; i += Lanes)
  {
    const float w = __ldcs(m.weights + i);
    const float4 v = __ldg(xs + __ldcs(m.columns + i));
    r += w * v.x;
    g += w * v.y;
    b += w * v.z;
  }
  for (int offset = Lanes / 2; offset > 0; offset /= 2)
  {
    r += __shfl_xor_sync(0xffffffffu, r, offset, Lanes);
    g += __shfl_xor_sync(0xffffffffu, g, offset, Lanes);
    b += __shfl_xor_sync(0xffffffffu, b, offset, Lanes);
  }
  return { r, g, b };
}

__device__ inline Vec3f albedoOf(const BounceParams& p, Index e)
{
  return p.albedo[e < p.vertexCount ? e : e - p.vertexCount];
}
__device__ inline Vec3f emissionOf(const BounceParams& p, Index e)
{
  return p.emission && e < p.vertexCount ? p.emission[e] : Vec3f(0.f);
}

template <int Lanes>
__global__ void gatherKernel(CsrView m, const Rgba* __restrict__ x, Rgba* __restrict__ y)
{
  const std::size_t t = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  const Index row = Index(t / Lanes);
  const Vec3f sum = gatherRow<Lanes>(m, x, row, int(t % Lanes));
  if (row < m.rows && t % Lanes == 0)
  {
    y[m.firstElement + row] = toRgba(sum);
  }
}

template <int Lanes>
__global__ void bounceKernel(CsrView w, BounceParams p, const Rgba* __restrict__ fixed,
  const Rgba* __restrict__ radiance, Rgba* __restrict__ indirect, Rgba* __restrict__ next)
{
  const std::size_t t = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
  const Index row = Index(t / Lanes);
  const Vec3f sum = gatherRow<Lanes>(w, radiance, row, int(t % Lanes));
  if (row < w.rows && t % Lanes == 0)
  {
    const Index e = w.firstElement + row;
    indirect[e] = toRgba(sum);
    if (next)
    {
      next[e] = toRgba(outgoingRadiance(albedoOf(p, e), toVec(fixed[e]), sum, emissionOf(p, e)));
    }
  }
}

__global__ void startKernel(BounceParams p, Index first, Index count, Rgba* fixed, Rgba* radiance)
{
  const Index i = blockIdx.x * blockDim.x + threadIdx.x;
  if (i < count)
  {
    const Index e = first + i;
    const Vec3f f = p.direct[e] + toVec(p.environment[e]);
    fixed[e] = toRgba(f);
    radiance[e] = toRgba(outgoingRadiance(albedoOf(p, e), f, Vec3f(0.f), emissionOf(p, e)));
  }
}

__global__ void finishKernel(FinishParams p, Vec3f* out)
{
  const Index e = blockIdx.x * blockDim.x + threadIdx.x;
  const BounceParams& b = p.bounce;
  if (e >= b.elements)
  {
    return;
  }
  const auto indirectAt = [&p, &b](std::size_t i) {
    const Vec3f bounced = p.indirect ? toVec(p.indirect[i]) : Vec3f(0.f);
    return bounced + toVec(b.environment[i]);
  };
  const Index v = e < b.vertexCount ? e : e - b.vertexCount;
  const Vec3f indirect = p.smoothing
    ? smoothElement(indirectAt, e, v, p.neighbourOffsets, p.neighbours, p.normals, p.cosFeatureAngle)
    : indirectAt(e);
  const Vec3f direct = b.direct[e];
  out[e] = direct;
  out[b.elements + e] = indirect;
  out[2 * std::size_t(b.elements) + e] =
    outgoingRadiance(albedoOf(b, e), direct, indirect, emissionOf(b, e));
}

unsigned blocksForRows(Index rows, int lanes)
{
  return unsigned((std::size_t(rows) * lanes + kThreads - 1) / kThreads);
}
}

int lanesForRows(Offset nonZeros, std::uint64_t rows)
{
  const double mean = rows ? double(nonZeros) / double(rows) : 0.0;
  return mean >= 48 ? 32 : mean >= 12 ? 16 : 8;
}

void gatherRgb(const CsrView& m, const Rgba* x, Rgba* y, cudaStream_t stream)
{
  if (m.rows == 0)
  {
    return;
  }
  const int lanes = m.lanes;
  const unsigned blocks = blocksForRows(m.rows, lanes);
  if (lanes == 32)
    gatherKernel<32><<<blocks, kThreads, 0, stream>>>(m, x, y);
  else if (lanes == 16)
    gatherKernel<16><<<blocks, kThreads, 0, stream>>>(m, x, y);
  else
    gatherKernel<8><<<blocks, kThreads, 0, stream>>>(m, x, y);
  LINKGI_CUDA_CHECK_LAUNCH("gatherKernel");
}

void startBounces(const BounceParams& p, Index first, Index count, Rgba* fixedIrradiance,
  Rgba* radiance, cudaStream_t stream)
{
  if (count)
  {
    startKernel<<<unsigned((std::size_t(count) + kThreads - 1) / kThreads), kThreads, 0, stream>>>(p, first, count, fixedIrradiance, radiance);
    LINKGI_CUDA_CHECK_LAUNCH("startKernel");
  }
}

void bounce(const CsrView& w, const BounceParams& p, const Rgba* fixedIrradiance,
  const Rgba* radiance, Rgba* indirect, Rgba* nextRadiance, cudaStream_t stream)
{
  if (w.rows == 0)
  {
    return;
  }
  const int lanes = w.lanes;
  const unsigned blocks = blocksForRows(w.rows, lanes);
  if (lanes == 32)
    bounceKernel<32><<<blocks, kThreads, 0, stream>>>(w, p, fixedIrradiance, radiance, indirect, nextRadiance);
  else if (lanes == 16)
    bounceKernel<16><<<blocks, kThreads, 0, stream>>>(w, p, fixedIrradiance, radiance, indirect, nextRadiance);
  else
    bounceKernel<8><<<blocks, kThreads, 0, stream>>>(w, p, fixedIrradiance, radiance, indirect, nextRadiance);
  LINKGI_CUDA_CHECK_LAUNCH("bounceKernel");
}

void finish(const FinishParams& p, Vec3f* out, cudaStream_t stream)
{
  if (p.bounce.elements)
  {
    finishKernel<<<unsigned((std::size_t(p.bounce.elements) + kThreads - 1) / kThreads), kThreads, 0, stream>>>(p, out);
    LINKGI_CUDA_CHECK_LAUNCH("finishKernel");
  }
}
}
