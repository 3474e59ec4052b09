// trajectory.h5 of a soft-sphere run ([trajectory], Lan 1994 sections 3.2-3.3): window-averaged
// velocities and unwrapped positions of the followed particles (TrajectorySampler), for velocity
// correlations and diffusion in `grainflow analyze`.
#pragma once

#include <optional>

#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/trajectory_sampler.hpp"

namespace grainflow::observe {

class WindowTrajectoryObserver final : public Observer {
 public:
  // `everyone`: every particle of the run (the ids to follow come from it).
  WindowTrajectoryObserver(const RunContext& run, const ParticleStore& everyone);

  std::string name() const override { return "trajectory"; }
  void sample(const Frame& now) override {
    sampler_->observe(*now.particles, *now.box, now.time - now.time_step, now.time);
  }
  void serialize(io::StateArchive& ar) override { ar(*sampler_); }
  void save_portable(io::StateArchive& ar) override {
    TrajectorySampler whole = *sampler_;
    whole.sum_open_window();
    ar(whole);
  }
  void load_portable(io::StateArchive& ar, bool keeper) override {
    ar(*sampler_);
    if (!keeper) sampler_->clear_open_window();
  }
  void save_streams(const std::string& folder) override {
    if (file_) file_->copy_to(folder + "/checkpoint_trajectory.h5");
  }
  void resume_streams(const std::string& folder) override {
    if (file_)
      io::resume_streams(folder + "/checkpoint_trajectory.h5", {&time_, &velocity_, &position_}, sampler_->taken());
  }
  void finish(OutputSink& out) override;

 private:
  std::optional<io::H5Writer> file_;  // rank 0's
  io::GrowingDataset time_, velocity_, position_;
  std::optional<TrajectorySampler> sampler_;
  long requested_ = 0;
};

}  // namespace grainflow::observe
