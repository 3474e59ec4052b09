// `grainflow sweep`: one case at many values of some keys. Every combination is loaded and validated
// first (exit 2 and nothing written if any is invalid); then each runs as a child process
// `grainflow run CASE -o OUTDIR/<name> --quiet --threads T --set ...`, at most `jobs` at a time, and
// OUTDIR/sweep.csv (one row per run: values, folder, exit status, summary.json's scalar fields) and
// OUTDIR/sweep.json (the command and the plan) are written. docs/OUTPUTS.md describes the folder.
#pragma once

#include <string>
#include <vector>

namespace grainflow::run {

struct SweepOptions {
  std::string case_path;
  std::vector<std::string> vary;       // KEY=v1,v2,... per --vary
  bool zip = false;                    // element by element instead of the Cartesian product
  std::string output_directory;        // "" = runs/<case stem>_sweep
  int jobs = 0;                        // 0 = $GRAINFLOW_JOBS, else the usable cores / threads
  std::vector<std::string> overrides;  // --set, applied to every run before the varied keys
  int threads = 0;                     // --threads of each run; 0 = not given, then 1
  bool quiet = false;                  // no progress lines
};

// Runs the sweep; returns the exit status: 0 all runs succeeded, 1 some failed, 2 invalid input
// (nothing written). `command` is the command line, recorded in sweep.json. Throws InputError for
// a malformed --vary, and RunError when the output folder cannot be written.
int run_sweep(const SweepOptions& options, const std::vector<std::string>& command);

}  // namespace grainflow::run
