// The particle loops' thread slices (dem/thread_slices.hpp): every index of [0, n) is visited
// exactly once, by contiguous slices in thread order, for team sizes above and below n; one
// thread runs the body on the caller as a single slice; partial results are combined in thread
// order, so a sum over slices equals the sum of the slices' sums taken in that order.
#include <gtest/gtest.h>

#include <cstddef>
#include <vector>

#include "grainflow/dem/thread_slices.hpp"

using grainflow::dem::for_each_slice;
using grainflow::dem::reduce_slices;

TEST(ThreadSlices, EveryIndexIsVisitedOnceInContiguousSlices) {
  for (int threads : {1, 2, 3, 5}) {
    for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{4}, std::size_t{1001}}) {
      std::vector<int> visits(n, 0);
      std::vector<std::size_t> begins(threads, n + 1), ends(threads, n + 1);
      for_each_slice(threads, n, [&](int t, std::size_t begin, std::size_t end) {
        begins[t] = begin;
        ends[t] = end;
        for (std::size_t i = begin; i < end; ++i) ++visits[i];  // slices are disjoint: no race
      });
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(visits[i], 1) << threads << " threads, n = " << n << ", i = " << i;
      // The slices that ran tile [0, n) in thread order (a team may be smaller than asked for).
      std::size_t next = 0;
      for (int t = 0; t < threads && begins[t] != n + 1; ++t) {
        EXPECT_EQ(begins[t], next);
        next = ends[t];
      }
      EXPECT_EQ(next, n) << threads << " threads, n = " << n;
    }
  }
}

TEST(ThreadSlices, OneThreadRunsASingleSliceOnTheCaller) {
  int calls = 0;
  for_each_slice(1, 7, [&](int t, std::size_t begin, std::size_t end) {
    ++calls;
    EXPECT_EQ(t, 0);
    EXPECT_EQ(begin, 0u);
    EXPECT_EQ(end, 7u);
  });
  EXPECT_EQ(calls, 1);
}

TEST(ThreadSlices, PartialsAreCombinedInThreadOrder) {
  // A non-commutative combination (appending digits) shows the order: slice t contributes its
  // first index, and the digits come out in increasing order after the starting value.
  struct Digits {
    std::vector<std::size_t> firsts;
    Digits& operator+=(const Digits& o) {
      firsts.insert(firsts.end(), o.firsts.begin(), o.firsts.end());
      return *this;
    }
  };
  for (int threads : {1, 2, 4}) {
    Digits start;
    start.firsts.push_back(99);
    const Digits all = reduce_slices(threads, 40, start, [](int, std::size_t begin, std::size_t end, Digits& d) {
      if (end > begin) d.firsts.push_back(begin);
    });
    ASSERT_GE(all.firsts.size(), 2u);
    EXPECT_EQ(all.firsts[0], 99u);
    EXPECT_EQ(all.firsts[1], 0u);
    for (std::size_t k = 2; k < all.firsts.size(); ++k) EXPECT_GT(all.firsts[k], all.firsts[k - 1]);
  }
  // A sum over 1000 indices is the closed form whatever the thread count.
  for (int threads : {1, 2, 3}) {
    const double sum = reduce_slices(threads, 1000, 0.5, [](int, std::size_t begin, std::size_t end, double& s) {
      for (std::size_t i = begin; i < end; ++i) s += static_cast<double>(i);
    });
    EXPECT_EQ(sum, 0.5 + 999.0 * 1000.0 / 2.0);  // integers below 2^53: exact in any order
  }
}
