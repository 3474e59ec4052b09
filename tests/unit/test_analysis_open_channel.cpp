// Campbell 1982 Appendix A's profile parameters (src/grainflow/analysis/open_channel.hpp) for
// profiles whose integrals are known in closed form: gamma = Gamma = 1 for uniform profiles,
// gamma = 4/3 for u linear from 0, Gamma = 2/3 for nu falling linearly to 0 at the surface, the
// part of a strip cut by the depth, and the critical Froude number (Gamma cos(alpha) / gamma)^(1/2).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grainflow/analysis/open_channel.hpp"

using namespace grainflow::analysis;

namespace {

// n strips of [0, depth], nu and u evaluated at the strip centres.
template <class Nu, class U>
std::vector<ProfileStrip> strips(int n, double depth, Nu&& nu, U&& u) {
  std::vector<ProfileStrip> out;
  for (int k = 0; k < n; ++k) {
    const double lo = depth * k / n, hi = depth * (k + 1) / n, mid = 0.5 * (lo + hi) / depth;
    out.push_back({lo, hi, nu(mid), u(mid)});
  }
  return out;
}

}  // namespace

TEST(OpenChannel, UniformProfilesHaveUnitParameters) {
  const auto p = open_channel_profile_parameters(strips(
                                                     7, 3.0, [](double) { return 0.6; }, [](double) { return 2.5; }),
                                                 3.0);
  EXPECT_NEAR(p.mean_solids_fraction, 0.6, 1e-12);
  EXPECT_NEAR(p.depth_mean_velocity, 2.5, 1e-12);
  EXPECT_NEAR(p.gamma, 1.0, 1e-12);
  EXPECT_NEAR(p.Gamma, 1.0, 1e-12);
  EXPECT_NEAR(critical_froude_number(p, std::cos(30.0 * M_PI / 180.0)), std::sqrt(std::cos(30.0 * M_PI / 180.0)),
              1e-12);
}

// u = U y/h with nu uniform: u_bar = U/2, gamma = int (2 eta)^2 = 4/3. nu = 2 nu_bar (1 - y/h):
// Gamma = 2 int eta 2 (1 - eta) = 2/3. With the strips' midpoint values the sums of squared
// midpoints, 1/3 - 1/(12 n^2), give gamma = 4/3 - 1/(3 n^2) and Gamma = 2/3 + 1/(3 n^2) (the linear
// sums are exact), so 1/n^2 bounds both deviations.
TEST(OpenChannel, LinearProfilesMatchTheirIntegrals) {
  const int n = 50;
  const auto shear =
      open_channel_profile_parameters(strips(
                                          n, 1.0, [](double) { return 0.5; }, [](double e) { return 3.0 * e; }),
                                      1.0);
  EXPECT_NEAR(shear.depth_mean_velocity, 1.5, 1e-12);
  EXPECT_NEAR(shear.gamma, 4.0 / 3.0, 1.0 / (n * n));
  const auto thinning =
      open_channel_profile_parameters(strips(
                                          n, 2.0, [](double e) { return 1.2 * (1.0 - e); }, [](double) { return 1.0; }),
                                      2.0);
  EXPECT_NEAR(thinning.mean_solids_fraction, 0.6, 1e-12);
  EXPECT_NEAR(thinning.Gamma, 2.0 / 3.0, 1.0 / (n * n));
  EXPECT_NEAR(thinning.gamma, 1.0, 1e-12);
}

// The depth cuts a strip: only the part below it counts; strips above it not at all.
TEST(OpenChannel, CountsOnlyWhatLiesBelowTheDepth) {
  const std::vector<ProfileStrip> s{
      {0.0, 1.0, 0.5, 1.0}, {1.0, 2.0, 0.5, 1.0}, {2.0, 3.0, 0.9, 7.0}, {3.0, 4.0, 0.9, 7.0}};
  const auto p = open_channel_profile_parameters(s, 2.5);
  // nu_bar = (0.5 * 2 + 0.9 * 0.5) / 2.5; u_bar = (1 * 2 + 7 * 0.5) / 2.5.
  EXPECT_NEAR(p.mean_solids_fraction, 1.45 / 2.5, 1e-12);
  EXPECT_NEAR(p.depth_mean_velocity, 5.5 / 2.5, 1e-12);
  // int nu u^2 = 0.5 * 2 + 0.9 * 49 * 0.5; int y nu = 0.5 * 2 + 0.9 * (2.5^2 - 2^2) / 2.
  const double nu_bar = 1.45 / 2.5, u_bar = 5.5 / 2.5;
  EXPECT_NEAR(p.gamma, (1.0 + 0.45 * 49.0) / (nu_bar * u_bar * u_bar * 2.5), 1e-12);
  EXPECT_NEAR(p.Gamma, 2.0 * (1.0 + 0.45 * 2.25) / (nu_bar * 2.5 * 2.5), 1e-12);
}
