// When a soft-sphere run does something recurring, counted in steps.
#pragma once

#include <algorithm>
#include <cmath>

namespace grainflow::observe {

// The steps at which something recurring every `interval` seconds happens: the step nearest to each
// k * interval (k = 1, 2, ...), so output times stay on the requested grid and the last one (at the
// end of a run whose duration is a multiple of the interval) is not lost. A fixed step count,
// round(interval / dt), drifts by up to dt/2 per interval and can skip the final output.
class Schedule {
 public:
  Schedule(double interval, double dt) : interval_(interval), dt_(dt) { advance(); }
  // True once per interval, at the first step at or after the next scheduled one.
  template <class Archive>
  void serialize(Archive& ar) {
    ar(k_, next_);
  }
  // Whether due(step) would be true, without advancing.
  bool due_at(long step) const { return interval_ > 0.0 && step >= next_; }
  bool due(long step) {
    if (interval_ <= 0.0 || step < next_) return false;
    advance();
    return true;
  }

 private:
  void advance() {
    ++k_;
    next_ = std::max(next_ + 1, static_cast<long>(std::llround(k_ * interval_ / dt_)));
  }
  double interval_, dt_;
  long k_ = 0, next_ = 0;
};

}  // namespace grainflow::observe
