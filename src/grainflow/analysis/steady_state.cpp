#include "grainflow/analysis/steady_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "grainflow/analysis/block_average.hpp"
#include "grainflow/analysis/least_squares_line.hpp"

namespace grainflow::analysis {
namespace {

constexpr std::size_t kMinBlocks = 8;  // blocking levels used down to 8 blocks (short tails)

double mean_of(std::span<const double> x) { return std::accumulate(x.begin(), x.end(), 0.0) / x.size(); }

struct Line {
  double slope = 0.0, stt = 0.0;  // least-squares slope; sum (t - t_mean)^2
  std::vector<double> residual;
};

Line fit_line(std::span<const double> t, std::span<const double> x) {
  const LeastSquaresLine fit = fit_least_squares_line(t, x);
  Line line;
  line.slope = fit.slope;
  line.stt = fit.sxx;
  for (std::size_t i = 0; i < t.size(); ++i) line.residual.push_back(x[i] - fit.at(t[i]));
  return line;
}

// A change below this fraction of the series' magnitude is round-off, not drift: an elastic gas's
// kinetic energy is constant to ~1e-13 and its "noise" is round-off too, so their ratio means nothing.
constexpr double kRoundOffChange = 1e-9;

// |difference| / error; an error of zero (a noiseless series) makes any real difference infinite.
double z_of(double difference, double error, double scale) {
  if (std::fabs(difference) <= kRoundOffChange * scale) return 0.0;
  if (error > 0.0) return std::fabs(difference) / error;
  return std::numeric_limits<double>::infinity();
}

}  // namespace

SteadyState detect_steady_state(std::span<const double> time, std::span<const double> value,
                                const SteadyStateOptions& options) {
  if (time.size() != value.size()) throw std::invalid_argument("detect_steady_state: time and value differ in length");
  SteadyState out;
  const std::size_t n = value.size();
  const std::size_t min_rest = std::max<std::size_t>(std::max<std::size_t>(options.min_samples, 4 * kMinBlocks),
                                                     static_cast<std::size_t>(std::ceil(options.min_fraction * n)));
  if (n < min_rest) {
    out.reason = "has only " + std::to_string(n) + " samples, too few to judge (at least " + std::to_string(min_rest) +
                 " needed)";
    out.too_short = true;
    return out;
  }
  double scale = 0.0;
  for (double v : value) scale = std::max(scale, std::fabs(v));
  const auto stride = static_cast<std::size_t>(std::max(1.0, std::round(options.step_fraction * n)));
  for (std::size_t start = 0; start + min_rest <= n; start += stride) {
    const auto t = time.subspan(start), x = value.subspan(start);
    const std::size_t half = x.size() / 2;
    // The noise: the long-run variance per sample, m se^2, of the detrended later half (m samples),
    // the part least touched by a transient.
    const Line later = fit_line(t.subspan(x.size() - half), x.subspan(x.size() - half));
    const double se = block_average(later.residual, kMinBlocks).standard_error;
    const double long_run_variance = half * se * se;
    const Line line = fit_line(t, x);
    const double span = t.back() - t.front();
    out.trend_z = z_of(line.slope * span, std::sqrt(long_run_variance / line.stt) * span, scale);
    const double difference = mean_of(x.subspan(x.size() - half)) - mean_of(x.subspan(0, half));
    out.halves_z = z_of(difference, std::sqrt(2.0 * long_run_variance / half), scale);
    if (out.trend_z < options.z_max && out.halves_z < options.z_max) {
      out.steady_from = time[start];
      return out;
    }
  }
  char text[160];
  std::snprintf(text, sizeof text,
                "still drifts over the last %g %% of the series (trend %.1f, halves %.1f standard errors)",
                100.0 * options.min_fraction, out.trend_z, out.halves_z);
  out.reason = text;
  return out;
}

}  // namespace grainflow::analysis
