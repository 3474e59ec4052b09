#include "grainflow/run/stiffness_search.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace grainflow::run {

double trial_stiffness(double start_k1, double factor, int n) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", start_k1 * std::pow(factor, n));
  return std::strtod(text, nullptr);
}

StiffnessSearchResult search_stiffness(const StiffnessSearchSettings& s,
                                       const std::function<double(double k1)>& max_overlap_ratio) {
  if (!(s.start_k1 > 0.0) || !std::isfinite(s.start_k1)) throw std::invalid_argument("the start K1 must be positive");
  if (!(s.factor > 1.0) || !std::isfinite(s.factor)) throw std::invalid_argument("the factor must be greater than 1");
  if (!(s.limit > 0.0)) throw std::invalid_argument("the overlap limit must be positive");
  if (s.max_trials < 1) throw std::invalid_argument("max_trials must be at least 1");

  StiffnessSearchResult result;
  auto run = [&](int n) {
    StiffnessTrial t;
    t.k1 = trial_stiffness(s.start_k1, s.factor, n);
    t.max_overlap_ratio = max_overlap_ratio(t.k1);
    t.passed = t.max_overlap_ratio <= s.limit;  // NaN fails
    result.trials.push_back(t);
    return t.passed;
  };
  auto room = [&] { return static_cast<int>(result.trials.size()) < s.max_trials; };

  if (!run(0)) {
    // Lan's procedure: increase K1 until the overlap stays within the limit.
    for (int n = 1; room(); ++n)
      if (run(n)) {
        result.chosen = result.trials.size() - 1;
        result.bracketed = true;
        break;
      }
    return result;
  }
  // The start already passes: step down until a trial fails; the last pass is the answer.
  result.descended = true;
  result.chosen = 0;
  for (int n = -1; room(); --n) {
    if (!run(n)) {
      result.bracketed = true;
      break;
    }
    result.chosen = result.trials.size() - 1;
  }
  return result;
}

}  // namespace grainflow::run
