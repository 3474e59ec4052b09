// Drives an event-driven case: events up to each output time, the measurements of INTERFACE.md
// (energies, temperature, collision counts, virial pressure, packing fraction), and the outputs.
#pragma once

#include "grainflow/run/run_options.hpp"
#include "grainflow/config/case_config.hpp"

namespace grainflow::run {

int run_edmd(const CaseConfig& c, const RunOptions& options);

}  // namespace grainflow::run
