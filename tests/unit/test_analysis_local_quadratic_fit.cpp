// Smoothed slopes of a profile by local least-squares quadratics
// (src/grainflow/analysis/local_quadratic_fit.hpp): exact for quadratics everywhere, the centred
// 5-point truncation error (17/30) h^2 f''' on a smooth analytic profile, skipped unusable points,
// and the propagated slope error of the centred window, sigma / (h sqrt 10).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "grainflow/analysis/local_quadratic_fit.hpp"

using namespace grainflow::analysis;

TEST(LocalQuadraticFit, ReproducesAQuadraticAndItsSlopeEverywhere) {
  // Uneven points, as strips' mean centres can be.
  const std::vector<double> x{0.0, 0.9, 2.1, 3.0, 4.2, 4.9, 6.3, 7.0};
  std::vector<double> y;
  for (double v : x) y.push_back(1.5 - 0.7 * v + 0.3 * v * v);
  const auto fit = local_quadratic_fit(x, y);
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_NEAR(fit[i].value, y[i], 1e-12) << i;
    EXPECT_NEAR(fit[i].slope, -0.7 + 0.6 * x[i], 1e-12) << i;  // ends included: the window shifts inwards
  }
}

// u(y) = sin(y) on an even grid of spacing h: at interior points the slope is the centred
// sum_k k y_k / (10 h), whose Taylor series gives cos(y) + (17/30) h^2 (-cos y) + O(h^4). Checked to
// 2 % of that leading error term (the O(h^4) term is (h^2/10 of it) ~0.1 % at h = 0.1), so a wrong
// window or weighting (e.g. a 3-point difference, error h^2 / 6) fails.
TEST(LocalQuadraticFit, InteriorSlopeHasTheCentredFivePointError) {
  const double h = 0.1;
  std::vector<double> x, y;
  for (int i = 0; i <= 40; ++i) x.push_back(i * h), y.push_back(std::sin(i * h));
  const auto fit = local_quadratic_fit(x, y);
  for (std::size_t i = 2; i + 2 < x.size(); ++i) {
    const double leading = -17.0 / 30.0 * h * h * std::cos(x[i]);
    EXPECT_NEAR(fit[i].slope - std::cos(x[i]), leading, 0.02 * 17.0 / 30.0 * h * h) << "x = " << x[i];
  }
  // At the ends the window is one-sided: still second order, error bounded by ~2 h^2 max|f'''|.
  for (std::size_t i : {std::size_t{0}, std::size_t{1}, x.size() - 2, x.size() - 1})
    EXPECT_NEAR(fit[i].slope, std::cos(x[i]), 2.0 * h * h) << "x = " << x[i];
}

TEST(LocalQuadraticFit, SkipsUnusablePointsAndPropagatesErrors) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), h = 2.0, sigma = 0.05;
  std::vector<double> x, y, e;
  for (int i = 0; i < 9; ++i) x.push_back(i * h), y.push_back(3.0 + 0.25 * i * h), e.push_back(sigma);
  y[8] = nan;  // an empty strip at the top
  const auto fit = local_quadratic_fit(x, y, e);
  EXPECT_TRUE(std::isnan(fit[8].slope));
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(fit[i].slope, 0.25, 1e-12) << i;
  // Centred window of 5 even points: slope = sum k y_k / (10 h), error sigma sqrt(sum k^2) / (10 h).
  EXPECT_NEAR(fit[4].slope_error, sigma / (h * std::sqrt(10.0)), 1e-12);
  // Off-centre windows weigh the points less evenly: a larger error.
  EXPECT_GT(fit[0].slope_error, fit[4].slope_error);
  // Fewer than 3 usable points: nothing to fit.
  const std::vector<double> two{1.0, nan, 2.0};
  const auto none = local_quadratic_fit(std::vector<double>{0.0, 1.0, 2.0}, two);
  for (const auto& f : none) EXPECT_TRUE(std::isnan(f.slope));
}
