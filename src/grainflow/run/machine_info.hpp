// The machine a run ran on, for run_log.json: enough to tell two timings' machines apart.
#pragma once

#include <string>

namespace grainflow::run {

std::string host_name();  // "unknown" when the system will not say
std::string cpu_model();  // /proc/cpuinfo's first "model name"; "unknown" elsewhere
int logical_cores();      // std::thread::hardware_concurrency(); 0 when unknown

}  // namespace grainflow::run
