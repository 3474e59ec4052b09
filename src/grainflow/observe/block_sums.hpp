// Error bars for long-term averages of profiles: each sample's per-bin sums (one `Sums` per zone or
// strip) are added into contiguous blocks of equal length. At most kMaxBlocks are kept; when full,
// neighbours merge pairwise and the block length doubles, so memory stays bounded however long the
// run. The standard error of an average then comes from Flyvbjerg-Petersen blocking of its
// per-block values (analysis/block_average). `Sums` needs a default state of zero and `+=`.
// A sample may carry a weight (e.g. the duration of the interval it sums, for rates); each block
// keeps the total weight of its samples.
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

#include "grainflow/analysis/block_average.hpp"

namespace grainflow::observe {

// At most this many blocks are kept (neighbours merge when full) ...
inline constexpr std::size_t kMaxErrorBlocks = 512;
// ... and fewer when there are many bins, so that blocks x bins stays under this many sums: a
// domain of 10^5 zones would otherwise keep 5 x 10^7 of them (gigabytes). Never fewer than 64
// blocks, enough for the blocking analysis (at least 2 kMinErrorBlocks).
inline constexpr std::size_t kMaxBlockedSums = std::size_t{1} << 19;
inline constexpr std::size_t kFewestErrorBlocks = 64;
// Blocking levels need at least this many blocks; below twice as many blocks the error is unknown.
inline constexpr std::size_t kMinErrorBlocks = 8;

template <class Sums>
class BlockSums {
 public:
  static constexpr std::size_t kMaxBlocks = kMaxErrorBlocks;

  // One sample's sums, one per bin (the bin count is fixed by the first sample), and its weight.
  void add(const std::vector<Sums>& sample, double weight = 1.0) {
    if (open_.empty()) {
      open_.assign(sample.size(), Sums{});
      // An even count (blocks merge pairwise) between kFewestErrorBlocks and kMaxBlocks.
      const std::size_t fit = kMaxBlockedSums / std::max<std::size_t>(1, sample.size());
      max_blocks_ = std::clamp(fit - fit % 2, kFewestErrorBlocks, kMaxBlocks);
    }
    for (std::size_t b = 0; b < sample.size(); ++b) open_[b] += sample[b];
    open_weight_ += weight;
    if (++open_samples_ < block_length_) return;
    blocks_.push_back(std::move(open_));
    weights_.push_back(open_weight_);
    open_.assign(sample.size(), Sums{});
    open_weight_ = 0.0;
    open_samples_ = 0;
    if (blocks_.size() < max_blocks_) return;
    for (std::size_t b = 0; b < max_blocks_ / 2; ++b) {
      std::vector<Sums> merged = std::move(blocks_[2 * b]);  // (b = 0 would self-move)
      for (std::size_t bin = 0; bin < merged.size(); ++bin) merged[bin] += blocks_[2 * b + 1][bin];
      blocks_[b] = std::move(merged);
      weights_[b] = weights_[2 * b] + weights_[2 * b + 1];
    }
    blocks_.resize(max_blocks_ / 2);
    weights_.resize(max_blocks_ / 2);
    block_length_ *= 2;
  }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(blocks_, weights_, open_, open_weight_, block_length_, open_samples_, max_blocks_);
  }

  // The full blocks, oldest first: blocks()[k][bin] sums block_length() samples.
  const std::vector<std::vector<Sums>>& blocks() const { return blocks_; }
  long block_length() const { return block_length_; }
  // The total weight of each full block's samples (the block length without weights).
  const std::vector<double>& block_weights() const { return weights_; }

 private:
  std::vector<std::vector<Sums>> blocks_;
  std::vector<double> weights_;
  std::vector<Sums> open_;
  double open_weight_ = 0.0;
  long block_length_ = 1, open_samples_ = 0;
  std::size_t max_blocks_ = kMaxBlocks;
};

// Standard error of the mean of per-block values; NaN with fewer than 2 kMinErrorBlocks of them.
inline double blocked_standard_error(const std::vector<double>& per_block) {
  if (per_block.size() < 2 * kMinErrorBlocks) return std::numeric_limits<double>::quiet_NaN();
  return analysis::block_average(per_block, kMinErrorBlocks).standard_error;
}

}  // namespace grainflow::observe
