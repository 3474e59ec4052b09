// Campbell's convergence check (1982 section 2.5) on an event-driven run's kinetic-energy history,
// as summary.json reports it.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "grainflow/io/json_writer.hpp"

namespace grainflow::run {

// summary.json's `steady_from` (null when the series still drifts, with a warning) and
// `averaged_when_steady`, and a warning when the long-term averages began (`averaging_start`, s)
// before the series became steady.
void report_steady_state(std::span<const double> time, std::span<const double> kinetic_energy, double averaging_start,
                         io::JsonObject& summary, std::vector<std::string>& warnings);

}  // namespace grainflow::run
