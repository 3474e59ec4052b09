#include "grainflow/observe/trajectory_sampler.hpp"

#include <algorithm>
#include <cmath>

namespace grainflow::observe {

TrajectorySampler::TrajectorySampler(std::vector<std::uint32_t> ids, double start, double window, long samples,
                                     Sink sink)
    : ids_(std::move(ids)), start_(start), window_(window), samples_(samples), sink_(std::move(sink)) {
  std::uint32_t largest = 0;
  for (auto id : ids_) largest = std::max(largest, id);
  column_of_id_.assign(ids_.empty() ? 0 : largest + 1, -1);
  for (std::size_t k = 0; k < ids_.size(); ++k) column_of_id_[ids_[k]] = static_cast<std::int32_t>(k);
  velocity_sum_.assign(3 * ids_.size(), 0.0);
  position_sum_.assign(3 * ids_.size(), 0.0);
}

void TrajectorySampler::observe(const ParticleStore& p, const PeriodicBox& box, double t0, double t1) {
  if (done() || t1 <= start_) return;
  t0 = std::max(t0, start_);
  // Split (t0, t1] at window ends. The relative tolerance absorbs the round-off of t = k dt: a
  // window that should end exactly at a step end but falls a hair short is closed there.
  while (t0 < t1 && !done()) {
    const double end = std::min(t1, start_ + (taken_ + 1) * window_);
    add(p, box, end - t0);
    t0 = end;
    if (filled_ >= window_ * (1.0 - 1e-9)) finish_window();
  }
}

void TrajectorySampler::add(const ParticleStore& p, const PeriodicBox& box, double weight) {
  if (weight <= 0.0) return;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.owned(i)) continue;  // MPI: its owner counts it
    const auto id = p.id[i];
    if (id >= column_of_id_.size()) continue;
    const int k = column_of_id_[id];
    if (k < 0) continue;
    const Vec3 x = box.unwrapped(p.position[i], p.image[i]);
    for (int a = 0; a < 3; ++a) {
      velocity_sum_[3 * k + a] += weight * p.velocity[i][a];
      position_sum_[3 * k + a] += weight * x[a];
    }
  }
  filled_ += weight;
}

void TrajectorySampler::finish_window() {
  // MPI: each rank integrated the tracked particles it owned; a particle that changed ranks within
  // the window has its integral in two parts.
  sum_open_window();
  const double inverse = 1.0 / filled_;
  for (double& v : velocity_sum_) v *= inverse;
  for (double& x : position_sum_) x *= inverse;
  sink_(start_ + (taken_ + 0.5) * window_, velocity_sum_, position_sum_);
  ++taken_;
  std::fill(velocity_sum_.begin(), velocity_sum_.end(), 0.0);
  std::fill(position_sum_.begin(), position_sum_.end(), 0.0);
  filled_ = 0.0;
}

}  // namespace grainflow::observe
