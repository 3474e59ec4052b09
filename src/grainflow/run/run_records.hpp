// The records of a `grainflow run` beside its results: OUTDIR/resolved_case.toml (the case with
// every default filled in and --set applied; `grainflow run` on it repeats the run bit for bit) and
// OUTDIR/run_log.json (version, commit, machine, threads, command line, wall-clock start and end).
#pragma once

#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include "grainflow/run/run_options.hpp"
#include "grainflow/config/case_config.hpp"

namespace grainflow::run {

// Writes resolved_case.toml, calls `run` (the engine; its exit status is returned), then writes
// run_log.json, also when `run` throws (the exception is passed on). Both files atomically.
using wall_clock = std::chrono::system_clock;

// run_log.json of a run that began at `start` and ended at `end` with `exit_status`.
void write_run_log(const std::string& dir, const CaseConfig& c, const RunOptions& options,
                   const std::vector<std::string>& command_line, wall_clock::time_point start,
                   wall_clock::time_point end, int exit_status);

int run_with_records(const CaseConfig& c, const RunOptions& options, const std::vector<std::string>& command_line,
                     const std::function<int()>& run);

}  // namespace grainflow::run
