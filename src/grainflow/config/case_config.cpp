#include "grainflow/config/case_config.hpp"

#include <cmath>

namespace grainflow {

double SpeciesConfig::mass() const { return M_PI / 6.0 * diameter * diameter * diameter * density; }

double trajectory_start(const CaseConfig& c) {
  return c.trajectory.start >= 0.0 ? c.trajectory.start : c.output.average_start;
}

double edmd_trajectory_interval(const CaseConfig& c) {
  if (c.trajectory.interval > 0.0) return c.trajectory.interval;
  return (c.run.duration - trajectory_start(c)) / static_cast<double>(c.trajectory.samples);
}

}  // namespace grainflow
