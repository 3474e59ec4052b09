#include "grainflow/run/steady_state_report.hpp"

#include <cstdio>
#include <limits>

#include "grainflow/analysis/steady_state.hpp"

namespace grainflow::run {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string format(const char* pattern, double a) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a);
  return text;
}

}  // namespace

void report_steady_state(std::span<const double> time, std::span<const double> kinetic_energy, double averaging_start,
                         io::JsonObject& summary, std::vector<std::string>& warnings) {
  const analysis::SteadyState steady = analysis::detect_steady_state(time, kinetic_energy);
  summary.number("steady_from", steady.steady_from ? *steady.steady_from : kNaN);
  // Whether the long-term averages describe the steady flow: it converged before they began.
  summary.boolean("averaged_when_steady", steady.steady_from && averaging_start >= *steady.steady_from);
  if (steady.too_short) {
    warnings.push_back("convergence not judged (Campbell 1982 section 2.5): the kinetic-energy history " +
                       steady.reason + "; use a smaller output.interval");
  } else if (!steady.steady_from) {
    warnings.push_back("the run has not converged (Campbell 1982 section 2.5): the kinetic energy " + steady.reason +
                       "; long-term averages describe a flow still changing");
  } else if (averaging_start < *steady.steady_from) {
    warnings.push_back("the long-term averages began at t = " + format("%g s", averaging_start) +
                       ", before the kinetic energy became steady at t = " + format("%g s", *steady.steady_from) +
                       ": raise output.average_start");
  }
}

}  // namespace grainflow::run
