// The search of `grainflow calibrate` (Lan 1994 section 4.1.3), apart from running anything: trial
// loading stiffnesses K1 on the geometric grid start * factor^n until the smallest one whose
// maximum overlap stays within the limit is bracketed by a failing neighbour K1 / factor.
//
// Lan starts below (K1_H / 100) and increases K1 "slightly" until alpha_max <= 0.01 d. When the
// first trial already passes, the start was stiffer than needed (a smaller time step than
// necessary), so the search steps down by the same factor until a trial fails and returns the
// smallest passing K1. Either way the answer K satisfies: K passes, K / factor fails, which makes
// it independent of the start up to the grid (if the overlap falls monotonically with K1).
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace grainflow::run {

struct StiffnessSearchSettings {
  double start_k1 = 0.0;  // N/m, first trial
  double factor = 1.25;   // > 1: K1 multiplies (or divides) by this between trials
  double limit = 0.01;    // largest acceptable max overlap / d
  int max_trials = 20;    // >= 1
};

struct StiffnessTrial {
  double k1 = 0.0;                 // N/m
  double max_overlap_ratio = 0.0;  // max overlap / d measured
  bool passed = false;             // max_overlap_ratio <= limit
};

struct StiffnessSearchResult {
  std::vector<StiffnessTrial> trials;  // in the order run
  std::optional<std::size_t> chosen;   // index of the answer: the smallest passing K1; none if no trial passed
  bool descended = false;              // the first trial passed, so the search stepped down
  // The answer has a failing neighbour K1 / factor among the trials. False when no trial passed, or
  // when stepping down used up max_trials before any trial failed.
  bool bracketed = false;
};

// The trial stiffnesses: start * factor^n rounded to 6 significant digits, so the value printed
// (and pasted into a case) is exactly the one tested. n may be negative.
double trial_stiffness(double start_k1, double factor, int n);

// Runs the search; `max_overlap_ratio(k1)` runs one trial and returns its max overlap / d (it may
// stop the trial early once the limit is exceeded: any value above the limit counts as a failure).
// Throws std::invalid_argument for start_k1 <= 0, factor <= 1, limit <= 0 or max_trials < 1.
StiffnessSearchResult search_stiffness(const StiffnessSearchSettings& settings,
                                       const std::function<double(double k1)>& max_overlap_ratio);

}  // namespace grainflow::run
