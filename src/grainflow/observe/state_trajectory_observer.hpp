// trajectory.h5 of an event-driven run: instantaneous states taken on a fixed time grid during the
// averaging period, as Campbell (1982, section 3.4.1) wrote the state to tape and read it back once
// the strip means were known; `grainflow analyze` turns them into velocity and pair distributions.
// Each sample holds the time, the followed particles' unwrapped positions, velocities and angular
// velocities, the y walls' positions, the strips' bounds and the periodic width.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/strip_layout.hpp"

namespace grainflow::observe {

class StateTrajectoryObserver final : public Observer {
 public:
  StateTrajectoryObserver(const RunContext& run, const Frame& start);

  std::string name() const override { return "trajectory"; }
  // When the next sample is due; +infinity once all are taken.
  double next_time() const override;
  // Records `s`, synchronized (every particle brought to s.time) at next_time().
  void sample(const Frame& s) override;
  // Commits the file with the samples taken; warns when the run ended before all of them.
  void finish(OutputSink& out) override;

  // Checkpoints: the count and the time grid here (a restart that runs longer keeps the grid the
  // run began with), the file as it is in a copy beside the checkpoint.
  void serialize(io::StateArchive& ar) override { ar(taken_, start_, interval_); }
  void save_streams(const std::string& folder) override { file_.copy_to(folder + "/checkpoint_trajectory.h5"); }
  void resume_streams(const std::string& folder) override {
    io::resume_streams(folder + "/checkpoint_trajectory.h5",
                       {&time_, &position_, &velocity_, &angular_velocity_, &wall_lo_at_, &wall_hi_at_, &strip_lo_,
                        &strip_hi_, &width_},
                       static_cast<std::size_t>(taken_));
  }

 private:
  io::H5Writer file_;
  StripLayout strips_;
  std::vector<std::int32_t> column_of_id_;  // -1 for particles not followed
  std::size_t followed_ = 0;
  int wall_lo_ = -1, wall_hi_ = -1;  // indices of the ylo and yhi walls, -1 when none
  double start_, interval_;
  long long requested_, taken_ = 0;
  io::GrowingDataset time_, position_, velocity_, angular_velocity_, wall_lo_at_, wall_hi_at_, strip_lo_, strip_hi_,
      width_;
  std::vector<double> row_x_, row_v_, row_w_;  // one sample, [followed, 3] each
};

}  // namespace grainflow::observe
