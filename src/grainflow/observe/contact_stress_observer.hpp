// A soft-sphere run's stresses (OUTPUTS.md, stresses.csv and walls.csv): the stress tensor strip by
// strip along y, its contact part from every touching contact's force carried along the branch
// vector from the partner's centre (or the contact point on a wall) to the particle's, shared among
// the strips by its length (observe/collision_stress.hpp), its kinetic part from the particles'
// velocities about the strip's mean; and each wall's load. Sampled every output.profile_interval
// from output.average_start, each sample standing for the interval since the previous one. The
// same files, columns and conventions as the event-driven engine's, the non-kinetic part named
// contact_*.
#pragma once

#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/observe/collision_stress.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/step_schedule.hpp"
#include "grainflow/observe/strip_layout.hpp"
#include "grainflow/observe/wall_stress.hpp"

namespace grainflow::observe {

class ContactStressObserver final : public Observer {
 public:
  ContactStressObserver(const RunContext& run, const Frame& start);

  std::string name() const override { return "stresses"; }
  void sample(const Frame& now) override;
  bool reads_contact_forces_at(long step) const override { return schedule_.due_at(step); }
  void serialize(io::StateArchive& ar) override { ar(stress_, walls_, schedule_, started_, last_); }
  void write(const Frame& last, OutputSink& out) override;

  // The long-term averages per strip (the weight integral from zero at the top, or from a top
  // wall's load).
  std::vector<StripStress> strip_stresses() const;
  std::vector<WallLoad> wall_loads() const { return walls_.averages(); }

 private:
  const CaseConfig& c_;
  RankReduce ranks_;              // each rank adds its own particles and contacts; sums over ranks at each sample
  const Frame* frame_ = nullptr;  // the run's frame (its box and walls), seen at the last sample
  StripLayout strips_;
  StressProfile stress_;
  WallLoads walls_;
  Schedule schedule_;
  bool started_ = false;
  double last_ = 0.0;  // s, the last sample
};

}  // namespace grainflow::observe
