// How an observer combines what each MPI rank measured over its own particles into the whole
// box's value, without gathering particles: sums element by element, and maxima (to agree on the
// length of a histogram). Default-constructed it is one rank, and both are the identity, so an
// observer is written once for a serial and a parallel run.
#pragma once

#include <cstddef>
#include <functional>

namespace grainflow::observe {

struct RankReduce {
  std::function<void(double* values, std::size_t count)> sum_in_place;
  std::function<double(double)> max_over_ranks;

  void sum(double* values, std::size_t count) const {
    if (sum_in_place) sum_in_place(values, count);
  }
  double max(double local) const { return max_over_ranks ? max_over_ranks(local) : local; }
};

}  // namespace grainflow::observe
