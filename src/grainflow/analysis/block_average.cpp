#include "grainflow/analysis/block_average.hpp"

#include <cmath>
#include <numeric>
#include <stdexcept>

namespace grainflow::analysis {
namespace {

// One blocking level. The blocks' own mean is used: it differs from the overall mean once an odd
// tail has been dropped, and c0 must measure the spread of the blocks that are there.
BlockLevel level_of(const std::vector<double>& x, std::size_t block_size) {
  const double n = static_cast<double>(x.size());
  const double m = std::accumulate(x.begin(), x.end(), 0.0) / n;
  double c0 = 0.0;
  for (double v : x) c0 += (v - m) * (v - m);
  c0 /= n;
  BlockLevel level;
  level.block_size = block_size;
  level.blocks = x.size();
  level.standard_error = std::sqrt(c0 / (n - 1.0));
  // Flyvbjerg-Petersen eq. (28): the variance estimate c0/(n'-1) is uncertain by a factor
  // sqrt(2/(n'-1)), hence the standard error by half of that.
  level.standard_error_error = level.standard_error / std::sqrt(2.0 * (n - 1.0));
  return level;
}

bool agree(const BlockLevel& a, const BlockLevel& b) {
  return std::fabs(a.standard_error - b.standard_error) <= a.standard_error_error + b.standard_error_error;
}

}  // namespace

BlockAverage block_average(std::span<const double> x, std::size_t min_blocks) {
  if (x.size() < 2) throw std::invalid_argument("block_average: needs at least 2 samples");
  BlockAverage out;
  out.mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(x.size());

  std::vector<double> blocks(x.begin(), x.end());
  for (std::size_t size = 1; blocks.size() >= 2; size *= 2) {
    out.levels.push_back(level_of(blocks, size));
    for (std::size_t i = 0; i < blocks.size() / 2; ++i) blocks[i] = 0.5 * (blocks[2 * i] + blocks[2 * i + 1]);
    blocks.resize(blocks.size() / 2);
  }
  out.naive_standard_error = out.levels.front().standard_error;

  // Levels usable for the plateau: 0 .. last, each with at least min_blocks blocks (their count
  // halves at each level, so they are a prefix).
  std::size_t usable = 0;
  while (usable < out.levels.size() && out.levels[usable].blocks >= min_blocks) ++usable;
  out.plateau_level = usable > 0 ? usable - 1 : 0;
  for (std::size_t p = 1; p + 1 < usable; ++p) {
    if (agree(out.levels[p - 1], out.levels[p]) && agree(out.levels[p], out.levels[p + 1])) {
      out.plateau_level = p;
      out.plateau_found = true;
      break;
    }
  }
  out.standard_error = out.levels[out.plateau_level].standard_error;
  out.standard_error_error = out.levels[out.plateau_level].standard_error_error;
  return out;
}

}  // namespace grainflow::analysis
