// Drives a DEM case from start to end: the time loop, the monitors (overlap halt, progress), the
// observers, and the output folder of INTERFACE.md. Returns the process exit status (0 or 1).
#pragma once

#include "grainflow/run/run_options.hpp"
#include "grainflow/config/case_config.hpp"

namespace grainflow::run {

int run_dem(const CaseConfig& c, const RunOptions& options);

}  // namespace grainflow::run
