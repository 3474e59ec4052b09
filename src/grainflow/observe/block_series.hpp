// Sums over sample intervals kept in contiguous blocks for block-averaged error bars, as the zone
// profile keeps them (observe/zone_profile.hpp): at most kMaxBlocks full blocks of equal length;
// when full, neighbours merge and the block length doubles. Each interval adds one vector of sums
// (one entry per strip or wall) and its duration. The standard error of a long-term average comes
// from Flyvbjerg-Petersen blocking of its per-block values (analysis/block_average).
#pragma once

#include <cstddef>
#include <limits>
#include <vector>

#include "grainflow/analysis/block_average.hpp"

namespace grainflow::observe {

template <class Sums>  // default-constructible, with operator+=
class BlockSeries {
 public:
  static constexpr std::size_t kMaxBlocks = 512, kMinErrorBlocks = 8;

  struct Block {
    std::vector<Sums> sums;
    double duration = 0.0;  // s
    long intervals = 0;
  };

  explicit BlockSeries(std::size_t width) : width_(width) { open_.sums.assign(width, Sums{}); }

  void add(const std::vector<Sums>& interval, double duration) {
    for (std::size_t k = 0; k < width_; ++k) open_.sums[k] += interval[k];
    open_.duration += duration;
    if (++open_.intervals < block_length_) return;
    blocks_.push_back(open_);
    open_ = Block{std::vector<Sums>(width_), 0.0, 0};
    if (blocks_.size() < kMaxBlocks) return;
    for (std::size_t b = 0; b < kMaxBlocks / 2; ++b) {
      blocks_[b] = blocks_[2 * b];
      merge(blocks_[b], blocks_[2 * b + 1]);
    }
    blocks_.resize(kMaxBlocks / 2);
    block_length_ *= 2;
  }

  // Full blocks only: the open one is shorter and would weigh as much as a full one.
  const std::vector<Block>& blocks() const { return blocks_; }

  // Standard error of the mean of per-block values; NaN below 2 kMinErrorBlocks blocks.
  static double error(const std::vector<double>& per_block) {
    if (per_block.size() < 2 * kMinErrorBlocks) return std::numeric_limits<double>::quiet_NaN();
    return analysis::block_average(per_block, kMinErrorBlocks).standard_error;
  }

 private:
  void merge(Block& to, const Block& from) const {
    for (std::size_t k = 0; k < width_; ++k) to.sums[k] += from.sums[k];
    to.duration += from.duration;
    to.intervals += from.intervals;
  }

  std::size_t width_;
  std::vector<Block> blocks_;
  Block open_;
  long block_length_ = 1;
};

}  // namespace grainflow::observe
