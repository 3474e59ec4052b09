// A run stalls when events keep coming at one instant, or crawls when time moves by round-off only
// (Zeno bounces, inelastic collapse). Each window of 100 N + 1000 events (some 50 collisions per
// particle) must move time forward by more than 1e-9 of its value; a healthy run would need ~10^10
// collisions per particle before that bound could bite.
#pragma once

#include <cmath>
#include <cstddef>

namespace grainflow::edmd {

class StallDetector {
 public:
  static long long window(std::size_t particles) { return 100 * static_cast<long long>(particles) + 1000; }

  void start(double time) { window_start_ = time; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(events_, window_start_);
  }

  // Counts one event at `time`; true when the window it closes moved time by too little (moved()
  // says how much, window_start() since when). A window that moved on starts the next.
  bool stalled(std::size_t particles, double time) {
    if (++events_ < window(particles)) return false;
    moved_ = time - window_start_;
    if (!(moved_ > 1e-9 * std::fabs(time))) return true;
    events_ = 0;
    window_start_ = time;
    return false;
  }
  double moved() const { return moved_; }
  double window_start() const { return window_start_; }

 private:
  long long events_ = 0;       // events since the window began
  double window_start_ = 0.0;  // s
  double moved_ = 0.0;         // s, over the last closed window
};

}  // namespace grainflow::edmd
