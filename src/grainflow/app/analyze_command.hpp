// `grainflow analyze OUTDIR`: post-processing of a finished run's trajectory.h5 (Lan 1994 sections
// 3.2-3.3, 4.4): velocity autocorrelation per component, mean-square displacement per component,
// and the self-diffusion coefficients from both (eqs. 3-2-5, 3-3-5, 4-4-2, 4-4-5, 4-4-6), with
// error bars from independent groups of particles. Writes OUTDIR/analysis/.
#pragma once

#include <string>

namespace grainflow::app {

struct AnalyzeOptions {
  long long max_lag = 0;  // samples; 0: the run's trajectory.max_lag
  int groups = 8;         // independent particle groups for the error bars
};

// Returns the exit status (0, or 2 when the folder has nothing to analyse).
int analyze_run(const std::string& output_directory, const AnalyzeOptions& options);

}  // namespace grainflow::app
