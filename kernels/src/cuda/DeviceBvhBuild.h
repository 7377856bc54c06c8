// What DeviceBvh.cu (Morton order, linear hierarchy, bounds, refit, depth-first order) and
// DeviceBvhPloc.cu (PLOC's clustering) share: the launch shape of the build kernels.
// Internal to the GPU BVH.
#pragma once

#include <cstddef>

namespace linkgi::cuda::bvhbuild
{
constexpr int kThreads = 256;

inline unsigned blocksFor(std::size_t n, int threads = kThreads)
{
  return unsigned((n + threads - 1) / threads);
}
}
