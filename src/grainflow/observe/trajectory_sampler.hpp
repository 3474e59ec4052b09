// Trajectory sampling for correlation functions and diffusion (Lan 1994 sections 3.2-3.3, 4.4):
// for chosen particles, consecutive windows of length t_s each yield one sample, the time average
// over the window of the velocity and of the unwrapped position. Lan sampled every t_s = 7.5 time
// steps (half the collision time at n = 15), "each sampled value ... a short term average value";
// a window that ends inside a time step takes the step's share by overlap, so t_s need not be a
// whole number of steps. Particles are followed by id, so re-sorting the store does not matter.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

class TrajectorySampler {
 public:
  // One finished window: its centre time, then velocity and unwrapped position of each tracked
  // particle (x, y, z per particle, in the order of `ids`).
  using Sink =
      std::function<void(double time, const std::vector<double>& velocity, const std::vector<double>& position)>;

  TrajectorySampler(std::vector<std::uint32_t> ids, double start, double window, long samples, Sink sink);

  // The state `p` holds the particles at time t1, the end of the step (t0, t1]; its velocities and
  // positions stand for the whole step.
  void observe(const ParticleStore& p, const PeriodicBox& box, double t0, double t1);
  // MPI: each rank observes its own particles and the windows' integrals are summed over the
  // ranks as each window closes (the sink then sees every particle on every rank).
  void set_reduce(RankReduce ranks) { ranks_ = std::move(ranks); }
  // A restart on another rank count: the open window's integrals summed over the ranks (collective),
  // to be kept by one rank; the others start their share from zero.
  void sum_open_window() {
    ranks_.sum(velocity_sum_.data(), velocity_sum_.size());
    ranks_.sum(position_sum_.data(), position_sum_.size());
  }
  void clear_open_window() {
    std::fill(velocity_sum_.begin(), velocity_sum_.end(), 0.0);
    std::fill(position_sum_.begin(), position_sum_.end(), 0.0);
  }
  bool done() const { return taken_ >= samples_; }
  long taken() const { return taken_; }
  const std::vector<std::uint32_t>& ids() const { return ids_; }

  template <class Archive>  // checkpoints: the open window and the count; the rest is the case's
  void serialize(Archive& ar) {
    ar(taken_, velocity_sum_, position_sum_, filled_);
  }

 private:
  void add(const ParticleStore& p, const PeriodicBox& box, double weight);
  void finish_window();

  std::vector<std::uint32_t> ids_;
  std::vector<std::int32_t> column_of_id_;  // -1 for particles not tracked
  double start_, window_;
  long samples_, taken_ = 0;
  Sink sink_;
  std::vector<double> velocity_sum_, position_sum_;  // time integrals over the open window
  double filled_ = 0.0;                              // s of the open window covered so far
  RankReduce ranks_;
};

}  // namespace grainflow::observe
