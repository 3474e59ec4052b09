// `grainflow calibrate`: the loading stiffness K1 of a Walton–Braun DEM case by Lan's (1994,
// section 4.1.3) maximum-overlap procedure. Starting from --start-k1, or from the Hertz-equivalent
// K1 / 100 (eq. 2-5-10 at the floor's peak speed; Lan's rule), each trial runs the case in-process
// (run_dem) with contact.k1 = the trial value, run.duration = --duration and run.halt_overlap =
// --limit, so a trial whose maximum overlap exceeds limit * d halts early; K1 grows by --factor
// until a trial stays within the limit (run/stiffness_search.hpp). If the first trial already
// passes, K1 steps down instead, and the smallest passing K1 is reported. Trials go to
// OUTDIR/trial_NN; OUTDIR/calibration.csv and calibration.json record them (docs/OUTPUTS.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace grainflow::run {

struct CalibrationOptions {
  std::string case_path;
  std::string output_directory;        // "" = runs/calibrate_<case stem>
  std::vector<std::string> overrides;  // --set, applied to every trial before the calibrated keys
  std::optional<double> duration;      // s; default: the case's run.duration
  double factor = 1.25;                // > 1
  double limit = 0.01;                 // max overlap / d
  std::optional<double> start_k1;      // N/m; default: Hertz-equivalent K1 / 100
  int max_trials = 20;
  int threads = 1;
  bool quiet = false;  // no progress lines of the trial runs
};

// Runs the calibration. Returns 0 when a passing K1 was found, 1 when none was within max_trials
// (the files are still written). Throws InputError (exit 2, nothing written) for bad options or an
// invalid case, RunError when a trial fails for a reason other than the overlap.
int run_calibration(const CalibrationOptions& options);

}  // namespace grainflow::run
