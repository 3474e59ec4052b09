// One scheduled event per particle, kept in an indexed binary min-heap on the event time:
// the next event is found in O(1), and re-scheduling a particle costs O(log N).
#pragma once

#include <cstdint>
#include <vector>

namespace grainflow::edmd {

class EventQueue {
 public:
  void reset(std::size_t particles, const std::vector<double>* times) {
    times_ = times;
    heap_.resize(particles);
    position_.resize(particles);
    for (std::size_t i = 0; i < particles; ++i) {
      heap_[i] = static_cast<std::uint32_t>(i);
      position_[i] = static_cast<std::uint32_t>(i);
    }
    for (std::size_t k = particles / 2; k-- > 0;) sift_down(k);
  }
  std::uint32_t top() const { return heap_.front(); }
  bool empty() const { return heap_.empty(); }
  // Call after the event time of particle `i` changed.
  void update(std::uint32_t i) {
    const std::size_t k = position_[i];
    if (k > 0 && key(heap_[(k - 1) / 2]) > key(i)) sift_up(k);
    else sift_down(k);
  }

 private:
  double key(std::uint32_t i) const { return (*times_)[i]; }
  void place(std::size_t k, std::uint32_t i) {
    heap_[k] = i;
    position_[i] = static_cast<std::uint32_t>(k);
  }
  void sift_up(std::size_t k) {
    const std::uint32_t item = heap_[k];
    const double t = key(item);
    while (k > 0) {
      const std::size_t parent = (k - 1) / 2;
      if (key(heap_[parent]) <= t) break;
      place(k, heap_[parent]);
      k = parent;
    }
    place(k, item);
  }
  void sift_down(std::size_t k) {
    const std::size_t n = heap_.size();
    const std::uint32_t item = heap_[k];
    const double t = key(item);
    while (true) {
      std::size_t child = 2 * k + 1;
      if (child >= n) break;
      if (child + 1 < n && key(heap_[child + 1]) < key(heap_[child])) ++child;
      if (key(heap_[child]) >= t) break;
      place(k, heap_[child]);
      k = child;
    }
    place(k, item);
  }

  const std::vector<double>* times_ = nullptr;
  std::vector<std::uint32_t> heap_;
  std::vector<std::uint32_t> position_;
};

}  // namespace grainflow::edmd
