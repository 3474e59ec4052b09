// Drives an event-driven case: events up to each output time, the measurements of INTERFACE.md
// (energies, temperature, collision counts, virial pressure, packing fraction), and the outputs.
#pragma once

#include "grainflow/app/run_options.hpp"
#include "grainflow/core/case_config.hpp"

namespace grainflow::app {

int run_edmd(const CaseConfig& c, const RunOptions& options);

}  // namespace grainflow::app
