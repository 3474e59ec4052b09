// One scheduled event per particle, kept in an indexed 4-ary min-heap on the event time: the next
// event is found in O(1), and re-scheduling a particle costs O(log N). Each heap node carries its
// own key (time), so sifting walks heap memory instead of looking up the times of scattered
// particles, and the four children of a node share one 64-byte cache line: at 10^6 particles a
// sift through the cold lower levels costs half the cache misses of a binary heap.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

namespace grainflow::edmd {

class EventQueue {
 public:
  void reset(std::size_t particles, const std::vector<double>* times) {
    times_ = times;
    size_ = particles;
    // Node k lives at slot k + 3, so children 4k+1 .. 4k+4 fill slots 4k+4 .. 4k+7: one line.
    // Slots past the last node hold +inf (never the least), so a sift compares four children
    // without asking how many there are: the last node's children may lie up to a line beyond it.
    lines_.assign((particles + kOffset + kArity - 1) / kArity + 2, Line{});
    for (Line& line : lines_)
      for (Node& node : line.node) node = {kInfinity, 0};
    heap_ = lines_.data()->node + kOffset;
    position_.resize(particles);
    for (std::size_t i = 0; i < particles; ++i) {
      heap_[i] = {(*times_)[i], static_cast<std::uint32_t>(i)};
      position_[i] = static_cast<std::uint32_t>(i);
    }
    for (std::size_t k = particles / kArity + 1; k-- > 0;) sift_down(k);
  }
  std::uint32_t top() const { return heap_[0].particle; }

  template <class Archive>  // the times stay where reset() pointed
  void serialize(Archive& ar) {
    ar(lines_, size_, position_);
    heap_ = lines_.data()->node + kOffset;
  }
  double top_time() const { return heap_[0].time; }  // the event time of top()
  bool empty() const { return size_ == 0; }
  // Call after the event time of particle `i` changed.
  void update(std::uint32_t i) {
    const std::size_t k = position_[i];
    heap_[k].time = (*times_)[i];
    if (k > 0 && heap_[(k - 1) / kArity].time > heap_[k].time) sift_up(k);
    else sift_down(k);
  }

 private:
  static constexpr std::size_t kArity = 4;
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();
  static constexpr std::size_t kOffset = kArity - 1;
  struct Node {
    double time;
    std::uint32_t particle;
  };
  struct alignas(64) Line {
    Node node[kArity];
  };
  static_assert(sizeof(Line) == 64);

  void place(std::size_t k, const Node& node) {
    heap_[k] = node;
    position_[node.particle] = static_cast<std::uint32_t>(k);
  }
  void sift_up(std::size_t k) {
    const Node item = heap_[k];
    while (k > 0) {
      const std::size_t parent = (k - 1) / kArity;
      if (heap_[parent].time <= item.time) break;
      place(k, heap_[parent]);
      k = parent;
    }
    place(k, item);
  }
  void sift_down(std::size_t k) {
    if (k >= size_) return;
    const Node item = heap_[k];
    while (true) {
      const std::size_t first = kArity * k + 1;
      if (first >= size_) break;
      // The least of the four children, without branches on their order (ties: the first).
      const Node* c = heap_ + first;
      const std::size_t low = c[1].time < c[0].time ? 1 : 0;
      const std::size_t high = c[3].time < c[2].time ? 3 : 2;
      const std::size_t child = first + (c[high].time < c[low].time ? high : low);
      if (heap_[child].time >= item.time) break;
      place(k, heap_[child]);
      k = child;
    }
    place(k, item);
  }

  const std::vector<double>* times_ = nullptr;
  std::vector<Line> lines_;
  Node* heap_ = nullptr;
  std::size_t size_ = 0;
  std::vector<std::uint32_t> position_;
};

}  // namespace grainflow::edmd
