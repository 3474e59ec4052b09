// The contiguous-block accumulator behind every block-averaged error bar (observe/block_sums.hpp):
// blocks stay contiguous and of equal length as they merge, their sums and weights are exact, and
// the open (partial) block is never reported.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grainflow/observe/block_sums.hpp"

using namespace grainflow::observe;

TEST(BlockSums, MergesNeighboursIntoEqualContiguousBlocksWithExactSumsAndWeights) {
  BlockSums<double> sums;
  // Sample s holds {s, 2s} and weighs 0.5 + s (a duration): exact in doubles for these sizes.
  const long samples = 3 * 512 + 7;  // past two merges, with a partial block left open
  for (long s = 0; s < samples; ++s) sums.add({double(s), 2.0 * s}, 0.5 + s);
  EXPECT_EQ(sums.block_length(), 4);  // 512 blocks of 1 -> 256 of 2 -> 256 of 4 at 1024 ... 1535 samples
  const auto& blocks = sums.blocks();
  ASSERT_EQ(blocks.size(), static_cast<std::size_t>(samples / 4));
  ASSERT_EQ(sums.block_weights().size(), blocks.size());
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    const double first = 4.0 * b;  // samples first .. first + 3, in order
    const double sum = 4.0 * first + 6.0;
    EXPECT_EQ(blocks[b][0], sum) << b;
    EXPECT_EQ(blocks[b][1], 2.0 * sum) << b;
    EXPECT_EQ(sums.block_weights()[b], 2.0 + sum) << b;
  }
}

TEST(BlockSums, ManyBinsKeepFewerBlocksSoMemoryStaysBounded) {
  // 2^19 / 40000 bins = 13 blocks would fit; never fewer than 64 are kept, so merging starts at 64
  // (to 32 of length 2) instead of 512. Sums stay exact: 40000 bins x 64 blocks at most.
  BlockSums<double> sums;
  const std::size_t bins = 40000;
  for (long s = 0; s < 100; ++s) sums.add(std::vector<double>(bins, double(s)));
  EXPECT_EQ(sums.block_length(), 2);  // 64 blocks of 1 -> 32 of 2 at sample 64; 50 of 2 after 100
  ASSERT_EQ(sums.blocks().size(), 50u);
  EXPECT_EQ(sums.blocks()[49][bins - 1], 98.0 + 99.0);
  // A few bins keep the full 512 (the test above): the limit only bites where it must.
  BlockSums<double> few;
  for (long s = 0; s < 511; ++s) few.add({1.0});
  EXPECT_EQ(few.block_length(), 1);
}

TEST(BlockSums, ErrorIsUnknownBelowTwiceTheFewestBlocks) {
  // Fewer than 2 kMinErrorBlocks blocks: too few blocking levels to see a plateau (the estimate
  // itself is tested in test_analysis_block_average).
  EXPECT_TRUE(std::isnan(blocked_standard_error(std::vector<double>(2 * kMinErrorBlocks - 1, 1.0))));
  EXPECT_FALSE(std::isnan(blocked_standard_error(std::vector<double>(2 * kMinErrorBlocks, 1.0))));
}
