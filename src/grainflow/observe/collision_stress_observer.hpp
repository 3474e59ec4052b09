// An event-driven run's collision measurements (Campbell 1982 sections 3.3, 3.4.2): the stress
// tensor strip by strip, the load on each wall and the collision-angle distribution, averaged from
// output.average_start (and output.average_start_collisions). Sampled on the strip profiles' grid
// (output.profile_interval); in between the engine reports each collision here. Writes stresses.csv,
// walls.csv and collision_angles.csv and adds the walls' keys to the summary.
#pragma once

#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/observe/collision_angles.hpp"
#include "grainflow/engine_api/collision_observer.hpp"
#include "grainflow/observe/collision_stress.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/strip_layout.hpp"
#include "grainflow/observe/wall_stress.hpp"

namespace grainflow::observe {

class CollisionStressObserver final : public Observer, public engine_api::CollisionObserver {
 public:
  CollisionStressObserver(const RunContext& run, const Frame& start);

  std::string name() const override { return "collision_stresses"; }
  double next_time() const override { return next_ * interval_; }
  // At a sample time, every particle current: starts averaging (and asking for every collision)
  // once its start is passed; afterwards closes the interval since the previous sample.
  void sample(const Frame& now) override;
  CollisionObserver* collision_observer() override { return started_ ? this : nullptr; }

  void serialize(io::StateArchive& ar) override { ar(stress_, walls_, angles_, started_, last_, next_); }

  void on_pair(const engine_api::PairCollision& c) override;
  void on_wall(const engine_api::WallCollision& c) override;

  // Closes a last, shorter interval if the run stopped between samples, then writes.
  void write(const Frame& last, OutputSink& out) override;
  // The long-term stress averages per strip (the weight integral starting from the top wall's load
  // in a Couette cell, from zero at a chute's free surface).
  std::vector<StripStress> strip_stresses() const;

 private:
  void close_interval(const Frame& now);
  double wall_area(int wall) const;  // m^(D-1), now
  void write_stresses(const std::string& path, const std::vector<StripStress>& strips) const;
  void write_walls(const std::string& path, const std::vector<WallLoad>& loads) const;
  void write_angles(const std::string& path, double shear_parameter) const;
  double shear_parameter(const std::vector<StripStress>& strips) const;

  const CaseConfig& c_;
  const Frame* frame_ = nullptr;  // the run's frame, seen at the last sample: its walls and box now
  int dim_;
  StripLayout strips_;
  StressProfile stress_;
  WallLoads walls_;
  CollisionAngles angles_;
  double interval_;
  long next_ = 1;
  bool started_ = false;
  double last_ = 0.0;  // s, the last sample
};

}  // namespace grainflow::observe
