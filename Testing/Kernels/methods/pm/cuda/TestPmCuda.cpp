// Photon mapping's CUDA internals: the photon tree built on the GPU.
#include "CudaFixtures.h"
#include "methods/pm/PmBackends.h"
#include "methods/pm/PointTree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace linkgi;

// The GPU's kd-tree (levels of segmented sorts, axes from sampled boxes) is a valid implicit
// median tree: the host's searches on its arrays find what brute force finds.
TEST(PmCuda, DeviceTreeSearchesEqualBruteForce)
{
  LINKGI_REQUIRE_CUDA_DEVICE();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (const std::size_t n : { std::size_t(5), std::size_t(9), std::size_t(1000), std::size_t(70001) })
  {
    std::vector<Vec3f> points;
    for (std::size_t i = 0; i < n; ++i)
    {
      Vec3f p(u(rng), i % 3 == 0 ? 0.f : u(rng), 0.1f * u(rng));
      points.push_back(i % 97 == 1 ? points[i - 1] : p);
    }
    std::vector<Index> order;
    std::vector<std::uint8_t> axes;
    pm::buildTreeOnDevice(points, order, axes);
    std::vector<Index> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 0; i < n; ++i)
    {
      ASSERT_EQ(sorted[i], Index(i)) << "the order is a permutation, n " << n;
    }
    const pm::PointTreeView view{ points.data(), order.data(), axes.data(), std::uint32_t(n) };
    std::vector<pm::Neighbour> heap(16), all;
    for (int q = 0; q < 200; ++q)
    {
      const Vec3f x = q < 50 ? points[(q * 7919) % n] : Vec3f(u(rng), u(rng), u(rng));
      all.clear();
      for (Index i = 0; i < Index(n); ++i)
      {
        all.push_back({ dot(points[i] - x, points[i] - x), i });
      }
      std::sort(all.begin(), all.end(), pm::nearer);
      const std::uint32_t found = pm::kNearest(view, x, 16, 3.4e38f, [](Index) { return true; }, heap.data());
      ASSERT_EQ(found, std::min<std::size_t>(16, n));
      std::sort(heap.begin(), heap.begin() + found, pm::nearer);
      for (std::uint32_t i = 0; i < found; ++i)
      {
        EXPECT_EQ(heap[i].index, all[i].index) << "n " << n << ", query " << q << ", rank " << i;
      }
    }
  }
}
