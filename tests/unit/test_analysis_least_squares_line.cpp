// The weighted least-squares line shared by the MSD slope, the steady-state trend test and the
// shear rates across strips (analysis/least_squares_line.hpp).
#include <gtest/gtest.h>

#include <vector>

#include "grainflow/analysis/least_squares_line.hpp"

using namespace grainflow::analysis;

TEST(LeastSquaresLine, RecoversAnExactLineFarFromTheOrigin) {
  // Centred sums: offsets of 1e6 with spacings of 1 lose nothing (the uncentred normal equations
  // would cancel ~12 of 16 digits).
  std::vector<double> x, y;
  for (int i = 0; i < 50; ++i) {
    x.push_back(1e6 + i);
    y.push_back(3.0 - 0.25 * x.back());
  }
  const LeastSquaresLine line = fit_least_squares_line(x, y);
  EXPECT_NEAR(line.slope, -0.25, 1e-12);
  EXPECT_NEAR(line.at(1e6 + 7.0), 3.0 - 0.25 * (1e6 + 7.0), 1e-6);
  EXPECT_DOUBLE_EQ(line.weight, 50.0);
}

TEST(LeastSquaresLine, WeightsAndSkippedPoints) {
  // Two points weighted 1 and 3 on a line, an outlier with weight 0: the line through the two.
  const std::vector<double> x = {0.0, 1.0, 2.0}, y = {1.0, 3.0, 100.0}, w = {1.0, 3.0, 0.0};
  const LeastSquaresLine line = fit_least_squares_line(x, y, w);
  EXPECT_NEAR(line.slope, 2.0, 1e-14);
  EXPECT_NEAR(line.intercept, 1.0, 1e-14);
  EXPECT_NEAR(line.x_mean, 0.75, 1e-15);  // (0 * 1 + 1 * 3) / 4
  // Mean zero in x and y: the slope is sum x y / sum x^2 = (2 + 2 + 2 + 2) / 10.
  const std::vector<double> xs = {-2.0, -1.0, 1.0, 2.0}, ys = {-1.0, -2.0, 2.0, 1.0};
  EXPECT_NEAR(fit_least_squares_line(xs, ys).slope, 0.8, 1e-14);
}

TEST(LeastSquaresLine, NoSpreadInXGivesNoSlope) {
  const std::vector<double> x = {2.0, 2.0, 2.0}, y = {1.0, 2.0, 3.0};
  const LeastSquaresLine line = fit_least_squares_line(x, y);
  EXPECT_EQ(line.sxx, 0.0);
  EXPECT_EQ(line.slope, 0.0);
  EXPECT_DOUBLE_EQ(line.y_mean, 2.0);
  EXPECT_EQ(fit_least_squares_line({}, {}).weight, 0.0);
}
