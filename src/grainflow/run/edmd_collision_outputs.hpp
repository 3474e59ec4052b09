// An event-driven run's collision measurements (Campbell 1982 sections 3.3, 3.4.2): the stress
// tensor strip by strip, the load on each wall and the collision-angle distribution, averaged from
// output.average_start (and output.average_start_collisions). The run calls sample() at every
// profile sample time and write() at the end; in between the engine reports each collision here.
// Writes stresses.csv, walls.csv and collision_angles.csv and adds the walls' keys to the summary.
#pragma once

#include <string>
#include <vector>

#include "grainflow/run/edmd_strips.hpp"
#include "grainflow/config/case_config.hpp"
#include "grainflow/observe/collision_observer.hpp"
#include "grainflow/edmd/edmd_state.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/observe/collision_angles.hpp"
#include "grainflow/observe/collision_stress.hpp"
#include "grainflow/observe/wall_stress.hpp"

namespace grainflow::edmd {
template <int Dim>
class EdmdEngine;
}

namespace grainflow::run {

class EdmdCollisionOutputs final : public observe::CollisionObserver {
 public:
  EdmdCollisionOutputs(const CaseConfig& c, const edmd::EdmdState& s);

  // At a sample time, every particle current: starts averaging (and observing `e`) once its start
  // is passed; afterwards closes the interval since the previous sample.
  template <int Dim>
  void sample(edmd::EdmdEngine<Dim>& e);
  // Closes a last, shorter interval if the run stopped between samples, and stops observing `e`.
  template <int Dim>
  void finish(edmd::EdmdEngine<Dim>& e);

  // After a restart restored this: observe `e` again if averaging had begun.
  template <int Dim>
  void resume(edmd::EdmdEngine<Dim>& e);

  template <class Archive>
  void serialize(Archive& ar) {
    ar(stress_, walls_, angles_, started_, last_);
  }

  void on_pair(const observe::PairCollision& c) override;
  void on_wall(const observe::WallCollision& c) override;

  void write(const std::string& dir, io::JsonObject& summary, std::vector<std::string>& warnings) const;
  // The long-term stress averages per strip (the weight integral starting from the top wall's load
  // in a Couette cell, from zero at a chute's free surface).
  std::vector<observe::StripStress> strip_stresses() const;

 private:
  double wall_area(int wall) const;  // m^(D-1), now
  void write_stresses(const std::string& path, const std::vector<observe::StripStress>& strips) const;
  void write_walls(const std::string& path, const std::vector<observe::WallLoad>& loads) const;
  void write_angles(const std::string& path, double shear_parameter) const;
  double shear_parameter(const std::vector<observe::StripStress>& strips) const;

  const CaseConfig& c_;
  const edmd::EdmdState* state_;
  int dim_;
  EdmdStrips strips_;
  observe::StressProfile stress_;
  observe::WallLoads walls_;
  observe::CollisionAngles angles_;
  bool started_ = false;
  double last_ = 0.0;  // s, the last sample
};

}  // namespace grainflow::run
