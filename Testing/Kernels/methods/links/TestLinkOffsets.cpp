// Link-entry offsets past 2^32 on the CPU, without the 40 GB such a matrix needs: the row
// offsets from per-row counts, and the gather over rows whose offsets start above 2^32.
#include "shared/Bounce.h"

#include <gtest/gtest.h>

#include <limits>

using namespace linkgi;

TEST(TestLinkOffsets, RowOffsetsFromCountsDoNotWrapAt32Bits)
{
  const Index big = std::numeric_limits<Index>::max();
  std::vector<Offset> offsets;
  exclusiveOffsets({ big, big, 5 }, 0, offsets);
  ASSERT_EQ(offsets.size(), 4u);
  EXPECT_EQ(offsets[1], Offset(big));
  EXPECT_EQ(offsets[2], 2 * Offset(big));
  EXPECT_EQ(offsets[3], 2 * Offset(big) + 5);
  // From a base above 2^32 (a slice of a larger matrix).
  const Offset base = (Offset(3) << 32) + 17;
  exclusiveOffsets({ 2, 0, 1 }, base, offsets);
  EXPECT_EQ(offsets, (std::vector<Offset>{ base, base + 2, base + 2, base + 3 }));
}

TEST(TestLinkOffsets, GatherReadsRowsWhoseOffsetsStartAbove4G)
{
  // Rows 0..2 of a matrix whose entries start at 5 * 2^32 + 3: only the slice is stored.
  const Offset base = (Offset(5) << 32) + 3;
  const std::vector<Offset> offsets = { base, base + 2, base + 2, base + 3 };
  const std::vector<Index> columns = { 1, 2, 0 };
  const std::vector<float> weights = { 0.5f, 2.f, 4.f };
  const std::vector<Vec3f> x = { { 1, 2, 3 }, { 4, 5, 6 }, { 7, 8, 9 } };
  std::vector<Vec3f> y(3, Vec3f(-1.f));
  gatherRgb(CsrRows{ offsets.data(), columns.data(), weights.data(), 3, base }, x.data(), y.data());
  EXPECT_EQ(y[0], x[1] * 0.5f + x[2] * 2.f);
  EXPECT_EQ(y[1], Vec3f(0.f));
  EXPECT_EQ(y[2], x[0] * 4.f);
}
