#include "linkgi/Error.h"
#include "shared/Sampling.h"

#include <gtest/gtest.h>

using namespace linkgi;

TEST(TestSampling, DirectionSetIsCosineWeighted)
{
  for (std::uint32_t n : { 16u, 64u, 256u, 1024u })
  {
    const std::vector<Vec3f> dirs = makeDirectionSet(n);
    ASSERT_EQ(dirs.size(), n);
    Vec3f mean(0.f);
    for (const Vec3f& d : dirs)
    {
      EXPECT_NEAR(length(d), 1.f, 1e-5f);
      EXPECT_GT(d.z, 0.f);
      mean += d / float(n);
    }
    // Under a cosine-weighted density E[cos theta] = 2/3 and the tangent components vanish.
    // Cell centres stop short of the horizon, where z = sqrt(1 - r^2) has a square-root
    // edge, so the midpoint rule converges as k^-1.5 (k = sqrt(n)).
    const float k = std::sqrt(float(n));
    EXPECT_NEAR(mean.z, 2.f / 3.f, 0.6f / (k * std::sqrt(k))) << n;
    EXPECT_NEAR(mean.x, 0.f, 1e-4f);
    EXPECT_NEAR(mean.y, 0.f, 1e-4f);
  }
}

TEST(TestSampling, BlocksOfSixteenAreCoherent)
{
  // Consecutive 4x4 blocks cover neighbouring cells: within a block of the 256-set, every
  // direction lies within ~40 degrees of the block's first one (a random pair: ~70 on average).
  const std::vector<Vec3f> dirs = makeDirectionSet(256);
  float worst = 1.f;
  for (std::size_t b = 0; b < 256; b += 16)
  {
    for (std::size_t i = 1; i < 16; ++i)
    {
      worst = std::min(worst, dot(dirs[b], dirs[b + i]));
    }
  }
  EXPECT_GT(worst, std::cos(50.f * kPi / 180.f));
}

TEST(TestSampling, NonSquareCountsAreRejected)
{
  EXPECT_THROW(makeDirectionSet(0), Error);
  EXPECT_THROW(makeDirectionSet(200), Error);
  EXPECT_NO_THROW(makeDirectionSet(36)); // k = 6: partial 4x4 blocks at the border
  EXPECT_EQ(makeDirectionSet(36).size(), 36u);
}

TEST(TestSampling, ConcentricMapPreservesArea)
{
  // Uniform points in the square give uniform points in the disk: E[r^2] = 1/2.
  const int k = 64;
  double r2 = 0.0;
  for (int y = 0; y < k; ++y)
  {
    for (int x = 0; x < k; ++x)
    {
      float dx, dy;
      concentricDisk((x + 0.5f) / k, (y + 0.5f) / k, dx, dy);
      EXPECT_LE(dx * dx + dy * dy, 1.f + 1e-5f);
      r2 += (dx * dx + dy * dy) / (k * k);
    }
  }
  EXPECT_NEAR(r2, 0.5, 1e-3);
}

TEST(TestSampling, VertexFramesAreOrthonormalAndTwisted)
{
  const Vec3f n = normalize(Vec3f(0.3f, -0.5f, 0.8f));
  const Frame a = vertexFrame(n, true, 7, 1), b = vertexFrame(n, true, 7, 2);
  for (const Frame& f : { a, b })
  {
    EXPECT_NEAR(dot(f.t, f.b), 0.f, 1e-5f);
    EXPECT_NEAR(dot(f.t, f.n), 0.f, 1e-5f);
    EXPECT_NEAR(length(f.t), 1.f, 1e-5f);
    EXPECT_NEAR(length(f.b), 1.f, 1e-5f);
    EXPECT_NEAR(dot(cross(f.t, f.b), n), 1.f, 1e-5f); // right-handed, z along the normal
  }
  EXPECT_LT(dot(a.t, b.t), 0.9999f); // different vertices, different twist
  const Frame c = vertexFrame(n, false, 7, 1), d = vertexFrame(n, false, 7, 2);
  EXPECT_EQ(c.t, d.t);
}
