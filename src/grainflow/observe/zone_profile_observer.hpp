// profiles.csv of a soft-sphere run: Lan's (1994) zone profiles along the gravity axis (Fig. 3.1),
// sampled every output.profile_interval from output.average_start, with the height of the density
// peak and the sample count in summary.json. Also where the zones lie, which the zone series, the
// convection field and the run's cell temperature share.
#pragma once

#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/step_schedule.hpp"
#include "grainflow/observe/zone_profile.hpp"

namespace grainflow::observe {

// Zones of output.zone_thickness (default: the reference diameter) across the box along gravity.
// They start at the floor's lowest reach, in whole zones below domain.lo, so that material under a
// floor shaken below its rest position is still counted.
struct ZoneLayout {
  int axis = 1;
  double lo = 0.0, hi = 0.0, thickness = 0.0;  // m
  double area = 1.0;                           // m^2, the box's cross-section normal to the axis

  explicit ZoneLayout(const RunContext& run);
  // An empty profile over these zones, summing over the run's ranks.
  ZoneProfile profile(const RunContext& run) const;
};

class ZoneProfileObserver final : public Observer {
 public:
  explicit ZoneProfileObserver(const RunContext& run);

  std::string name() const override { return "profiles"; }
  void sample(const Frame& now) override {
    // Each rank samples its own particles; the zone sums are added over the ranks.
    if (schedule_.due(now.step) && now.step >= average_from_) profile_.sample(*now.particles);
  }
  void serialize(io::StateArchive& ar) override { ar(profile_, schedule_); }
  void write(const Frame& last, OutputSink& out) override;

 private:
  RunContext run_;
  ZoneProfile profile_;
  Schedule schedule_;
  long average_from_ = 0;
};

}  // namespace grainflow::observe
