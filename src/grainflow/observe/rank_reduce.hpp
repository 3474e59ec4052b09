// How an observer combines what each MPI rank measured over its own particles into the whole
// box's value, without gathering particles: sums element by element, and maxima (to agree on the
// length of a histogram). Default-constructed it is one rank, and both are the identity, so an
// observer is written once for a serial and a parallel run.
#pragma once

#include <cstddef>
#include <cstring>
#include <functional>
#include <type_traits>
#include <vector>

namespace grainflow::observe {

struct RankReduce {
  std::function<void(double* values, std::size_t count)> sum_in_place;
  std::function<double(double)> max_over_ranks;

  void sum(double* values, std::size_t count) const {
    if (sum_in_place) sum_in_place(values, count);
  }
  double max(double local) const { return max_over_ranks ? max_over_ranks(local) : local; }

  // Sums records made of doubles only (a struct of doubles, Vec3s and tensors) element by element.
  template <class Record>
  void sum_records(std::vector<Record>& records) const {
    static_assert(std::is_trivially_copyable_v<Record> && sizeof(Record) % sizeof(double) == 0,
                  "sum_records: a record of doubles only");
    if (!sum_in_place || records.empty()) return;
    std::vector<double> flat(records.size() * sizeof(Record) / sizeof(double));
    std::memcpy(flat.data(), records.data(), flat.size() * sizeof(double));
    sum_in_place(flat.data(), flat.size());
    std::memcpy(static_cast<void*>(records.data()), flat.data(), flat.size() * sizeof(double));  // trivially copyable
  }
};

}  // namespace grainflow::observe
