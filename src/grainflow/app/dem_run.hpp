// Drives a DEM case from start to end: the time loop, the monitors (overlap halt, progress), the
// observers, and the output folder of INTERFACE.md. Returns the process exit status (0 or 1).
#pragma once

#include "grainflow/app/run_options.hpp"
#include "grainflow/core/case_config.hpp"

namespace grainflow::app {

int run_dem(const CaseConfig& c, const RunOptions& options);

}  // namespace grainflow::app
