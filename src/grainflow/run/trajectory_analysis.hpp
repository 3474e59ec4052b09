// `grainflow analyze OUTDIR`: post-processing of a finished run's trajectory.h5 (Lan 1994 sections
// 3.2-3.3, 4.4): velocity autocorrelation per component, mean-square displacement per component,
// and the self-diffusion coefficients from both (eqs. 3-2-5, 3-3-5, 4-4-2, 4-4-5, 4-4-6), with
// error bars from independent groups of particles. An event-driven run's trajectory.h5 (instantaneous
// states) gives Campbell's velocity and pair distributions instead (Campbell 1982 section 3.4; see
// run/distribution_analysis.hpp). Writes OUTDIR/analysis/.
#pragma once

#include <string>

namespace grainflow::run {

struct AnalyzeOptions {
  long long max_lag = 0;  // samples; 0: the run's trajectory.max_lag
  int groups = 8;         // independent particle groups for the error bars
  int first_strip = 0;    // edmd: the strips whose particles the velocity distributions count
  int last_strip = -1;    //   (inclusive, from the bottom wall; -1: the top strip)
};

// Returns the exit status (0, or 2 when the folder has nothing to analyse).
int analyze_run(const std::string& output_directory, const AnalyzeOptions& options);

}  // namespace grainflow::run
