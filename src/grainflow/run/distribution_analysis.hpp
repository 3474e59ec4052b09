// `grainflow analyze` on an event-driven run: Campbell's (1982 section 3.4) velocity distributions
// (X1..X5 with generalized-Maxwellian fits and S) and pair distributions (normal and parallel) from
// the instantaneous states in trajectory.h5. Writes analysis/velocity_distributions.csv,
// analysis/pair_distributions.csv and analysis/distributions.json.
#pragma once

#include <string>

#include "grainflow/analysis/state_samples.hpp"
#include "grainflow/run/trajectory_analysis.hpp"

namespace grainflow::run {

// Whether trajectory.h5 holds an event-driven run's instantaneous states.
bool is_edmd_trajectory(const std::string& path);
analysis::StateSamples read_state_samples(const std::string& path);
void analyze_distributions(const std::string& output_directory, const AnalyzeOptions& options);

}  // namespace grainflow::run
