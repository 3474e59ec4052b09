// Smoothed value and slope of a sampled profile (e.g. du/dy across Campbell's strips, which he took
// from cubic-spline fits): at each point, a quadratic fitted by least squares to the `window`
// nearest usable points (centred where possible, shifted inwards at the ends), evaluated there.
// A least-squares quadratic reproduces any quadratic exactly and, on an even grid of spacing h,
// the centred 5-point slope is sum_k k y_k / (10 h) (k = -2..2), with truncation error
// (17/30) h^2 f''' — so noise is smoothed while curvature adds no bias.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace grainflow::analysis {

struct FitPoint {
  double value = 0.0;        // the fitted quadratic at x_i
  double slope = 0.0;        // its derivative at x_i
  double slope_error = 0.0;  // propagated from the points' errors, taken as independent
};

// x: increasing positions; y: values, NaN where unusable (skipped); y_error: standard errors of
// y (NaN or empty: slope_error NaN). At a point with NaN y, or with fewer than 3 usable points in
// all, the fit reads NaN. `window` >= 3; fewer usable points than that make the window smaller.
std::vector<FitPoint> local_quadratic_fit(std::span<const double> x, std::span<const double> y,
                                          std::span<const double> y_error = {}, std::size_t window = 5);

}  // namespace grainflow::analysis
