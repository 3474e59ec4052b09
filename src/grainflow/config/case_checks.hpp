// Helpers of the checks that combine several keys of a case (each engine's in its own layer).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include "grainflow/config/case_config.hpp"
#include "grainflow/core/error.hpp"

namespace grainflow::case_checks {

// A count or size for a message: an integer as digits, else in %g form.
inline std::string fmt_number(double x) {
  char text[64];
  std::snprintf(text, sizeof text, x < 1e15 && x == std::floor(x) ? "%.0f" : "%g", x);
  return text;
}

[[noreturn]] inline void fail(const CaseConfig& c, const std::string& key, const std::string& reason) {
  throw InputError(c.path, key, reason);
}

}  // namespace grainflow::case_checks
