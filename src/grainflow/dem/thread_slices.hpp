#pragma once
// Loops over the particles split into one contiguous slice per OpenMP thread, with per-thread
// partial results combined in thread order. With one thread the body runs on the caller and no
// parallel region is entered: libgomp ends every region, even a one-thread one, with a futex
// system call (about 1.5 µs), which is more than a whole step's work for a few dozen particles.
#include <cstddef>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace grainflow::dem {

// One thread's own data on cache lines of its own: what threads write side by side in a vector
// (partial sums, a std::vector's end pointer as it grows) would otherwise share a line, and every
// write by one thread would take the line from the other.
template <class T>
struct alignas(64) ThreadSlot {
  T value{};
};

// Calls body(t, begin, end) once per thread t of a team of at most `threads`, the slices
// [n t / team, n (t + 1) / team) covering [0, n); body(0, 0, n) when threads <= 1.
template <class Body>
void for_each_slice(int threads, std::size_t n, Body&& body) {
  if (threads <= 1) {
    body(0, std::size_t{0}, n);
    return;
  }
#pragma omp parallel num_threads(threads)
  {
#ifdef _OPENMP
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    const std::size_t team = static_cast<std::size_t>(omp_get_num_threads());
#else
    const std::size_t t = 0, team = 1;
#endif
    body(static_cast<int>(t), n * t / team, n * (t + 1) / team);
  }
}

// As for_each_slice, body(t, begin, end, partial) adding to its own thread's `partial` (a
// default-constructed T); returns `total` with every partial added by T's += in thread order.
template <class T, class Body>
T reduce_slices(int threads, std::size_t n, T total, Body&& body) {
  if (threads <= 1) {
    T partial{};
    body(0, std::size_t{0}, n, partial);
    total += partial;
    return total;
  }
  std::vector<ThreadSlot<T>> partials(static_cast<std::size_t>(threads));
  for_each_slice(threads, n, [&](int t, std::size_t begin, std::size_t end) {
    body(t, begin, end, partials[static_cast<std::size_t>(t)].value);
  });
  for (const ThreadSlot<T>& slot : partials) total += slot.value;
  return total;
}

}  // namespace grainflow::dem
