// The CUDA engine's split of a relink among identical GPUs (equalCostSplit): contiguous
// ranges of equal cost by the last link stage's batches. Host logic: runs without a GPU.
#include "methods/links/cuda/CudaEngine.h"

#include <gtest/gtest.h>

using namespace linkgi;
using namespace linkgi::cuda;

TEST(CudaSchedule, EvenCostsSplitEvenly)
{
  const std::vector<BatchCost> last = { { 0, 25, 1.0 }, { 25, 25, 1.0 }, { 50, 25, 1.0 }, { 75, 25, 1.0 } };
  EXPECT_EQ(equalCostSplit(last, 100, 2), (std::vector<Index>{ 0, 50, 100 }));
  EXPECT_EQ(equalCostSplit(last, 100, 4), (std::vector<Index>{ 0, 25, 50, 75, 100 }));
}

TEST(CudaSchedule, ExpensiveElementsGetShorterRanges)
{
  // The first half costs three times the second: half of the 40 ms lies 2/3 into the first
  // batch, so the first GPU takes 33 elements, the second 67. The batches' order in the list
  // does not matter (they come from several GPUs).
  const std::vector<BatchCost> last = { { 50, 50, 10.0 }, { 0, 50, 30.0 } };
  EXPECT_EQ(equalCostSplit(last, 100, 2), (std::vector<Index>{ 0, 33, 100 }));
}

TEST(CudaSchedule, EveryRangeHoldsAnElement)
{
  // All the cost in the first element: the others still get one element each.
  const std::vector<BatchCost> last = { { 0, 1, 100.0 }, { 1, 9, 1e-6 } };
  const std::vector<Index> split = equalCostSplit(last, 10, 4);
  ASSERT_EQ(split.size(), 5u);
  for (std::size_t k = 0; k + 1 < split.size(); ++k)
  {
    EXPECT_LT(split[k], split[k + 1]) << k;
  }
  EXPECT_EQ(split.front(), 0u);
  EXPECT_EQ(split.back(), 10u);
}

TEST(CudaSchedule, BatchesThatDoNotCoverTheElementsGiveNoPlan)
{
  EXPECT_TRUE(equalCostSplit({}, 100, 2).empty()) << "no last stage";
  EXPECT_TRUE(equalCostSplit({ { 0, 40, 1.0 }, { 50, 50, 1.0 } }, 100, 2).empty()) << "a gap";
  EXPECT_TRUE(equalCostSplit({ { 0, 50, 1.0 }, { 50, 50, 1.0 } }, 120, 2).empty()) << "other elements";
  EXPECT_TRUE(equalCostSplit({ { 0, 50, 1.0 }, { 50, 50, 0.0 } }, 100, 2).empty()) << "an unmeasured batch";
  EXPECT_TRUE(equalCostSplit({ { 0, 1, 1.0 } }, 1, 2).empty()) << "fewer elements than parts";
}
