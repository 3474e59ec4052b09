// Weighted least-squares straight line y = intercept + slope x, computed about the weighted means
// (centred sums keep the normal equations well conditioned for long or offset ranges). Used for
// the MSD's limiting slope, trends in time series and shear rates across strips.
#pragma once

#include <cstddef>
#include <span>

namespace grainflow::analysis {

struct LeastSquaresLine {
  double slope = 0.0, intercept = 0.0;
  double x_mean = 0.0, y_mean = 0.0;  // weighted means
  double sxx = 0.0;                   // sum w (x - x_mean)^2: 0 when x does not vary (slope then 0)
  double weight = 0.0;                // sum w
  double at(double x) const { return intercept + slope * x; }
};

// Points with weight <= 0 (or NaN) are skipped; `w` empty: every weight 1.
inline LeastSquaresLine fit_least_squares_line(std::span<const double> x, std::span<const double> y,
                                               std::span<const double> w = {}) {
  LeastSquaresLine line;
  auto weight = [&](std::size_t i) { return w.empty() ? 1.0 : (w[i] > 0.0 ? w[i] : 0.0); };
  double sx = 0.0, sy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    line.weight += weight(i);
    sx += weight(i) * x[i];
    sy += weight(i) * y[i];
  }
  if (!(line.weight > 0.0)) return line;
  line.x_mean = sx / line.weight;
  line.y_mean = sy / line.weight;
  double sxy = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!(weight(i) > 0.0)) continue;
    const double dx = x[i] - line.x_mean;
    line.sxx += weight(i) * dx * dx;
    sxy += weight(i) * dx * (y[i] - line.y_mean);
  }
  line.slope = line.sxx > 0.0 ? sxy / line.sxx : 0.0;
  line.intercept = line.y_mean - line.slope * line.x_mean;
  return line;
}

}  // namespace grainflow::analysis
