// Savage and Jeffrey's collision-angle distribution in Campbell's 2D form
// (analysis/savage_jeffrey.hpp): a probability density on [0, pi) for every S, isotropic at S = 0,
// favouring 90-180 degrees for a velocity that grows with y.
#include <gtest/gtest.h>

#include <cmath>

#include "grainflow/analysis/savage_jeffrey.hpp"

using grainflow::analysis::savage_jeffrey_angle_density;
using grainflow::analysis::savage_jeffrey_shear_parameter;

namespace {

// The integrand is smooth and pi-periodic, so the trapezoidal rule on 2000 points is exact to
// round-off (its error falls faster than any power of the step).
double integral(double s, double from, double to, int points = 2000) {
  const double h = (to - from) / points;
  double sum = 0.0;
  for (int k = 0; k < points; ++k) sum += savage_jeffrey_angle_density(from + (k + 0.5) * h, s);
  return sum * h;
}

}  // namespace

TEST(SavageJeffrey, IntegratesToOneForEveryS) {
  for (double s : {0.0, 0.45, 0.9, 2.0, 5.0}) EXPECT_NEAR(integral(s, 0.0, M_PI), 1.0, 1e-13) << "S = " << s;
}

TEST(SavageJeffrey, IsotropicAtZeroShear) {
  for (double theta : {0.0, 0.3, M_PI / 2.0, 2.5})
    EXPECT_DOUBLE_EQ(savage_jeffrey_angle_density(theta, 0.0), 1.0 / M_PI);
}

TEST(SavageJeffrey, FavoursTheSecondQuadrantWhenTheFlowSpeedsUpWithHeight) {
  // Campbell's Fig. 3.31b: the faster layer above overtakes from behind, theta in (90, 180) degrees.
  const double s = 0.9;
  EXPECT_GT(integral(s, M_PI / 2.0, M_PI), integral(s, 0.0, M_PI / 2.0));
  EXPECT_GT(savage_jeffrey_angle_density(3.0 * M_PI / 4.0, s), 1.0 / M_PI);
  EXPECT_LT(savage_jeffrey_angle_density(M_PI / 4.0, s), 1.0 / M_PI);
  // Mirror symmetry: reversing the shear mirrors theta about 90 degrees.
  EXPECT_DOUBLE_EQ(savage_jeffrey_angle_density(0.4, s), savage_jeffrey_angle_density(M_PI - 0.4, -s));
  // Along and across the flow (0 and 90 degrees) the shear does not matter.
  EXPECT_NEAR(savage_jeffrey_angle_density(M_PI / 2.0, s), 1.0 / M_PI, 1e-16);
}

TEST(SavageJeffrey, ShearParameter) {
  EXPECT_DOUBLE_EQ(savage_jeffrey_shear_parameter(1.0, 0.5, 0.25), 2.0);  // 2 R du/dy / sqrt(<v'^2>)
  EXPECT_EQ(savage_jeffrey_shear_parameter(1.0, 0.5, 0.0), 0.0);
}
