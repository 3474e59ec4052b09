// The mean flow a case starts with (config/initial_flow.hpp), the same for both engines: Campbell's
// Couette start (linear across y from the ylo wall's velocity to the yhi wall's, section 2.8), his
// chute start (listing COL007's fit, F(0) = 0.20 slip at the floor, F(1) = 1 at the top), a uniform
// initial_velocity, and Lees-Edwards' homogeneous shear, zero at mid-height.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "grainflow/config/initial_flow.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "test_support.hpp"

using namespace grainflow;

namespace {

std::string discs_between_walls(const std::string& profile) {
  return R"([engine]
kind = "dem"
dimension = 2
[domain]
lo = [0.0, 2.0, 0.0]
hi = [12.0, 14.0, 1.0]
boundary = { x = "periodic", y = "wall", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "disc"
diameter = 1.0
density = 1.0
count = 60
[particles]
init = "lattice"
initial_velocity = [0.5, 0.0, 0.0]
initial_profile = ")" +
         profile + R"("
[contact]
model = "linear_dashpot"
kn = 1.0e4
[walls.ylo]
velocity = [-1.0, 0.0, 0.0]
[walls.yhi]
velocity = [3.0, 0.0, 0.0]
[run]
duration = 1.0
)";
}

}  // namespace

// The DEM discs start on the case's profile exactly: u = 0.5 + (-1) + 4 (y - 2) / 12 along x.
TEST(InitialFlow, SoftDiscsStartOnCampbellsCouetteProfile) {
  const CaseConfig c = load_case_from_string(discs_between_walls("couette"), "couette.toml");
  const dem::DemState s = dem::build_dem_state(c);
  ASSERT_EQ(s.particles.size(), 60u);
  double spread = 0.0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const Vec3& x = s.particles.position[i];
    const Vec3& v = s.particles.velocity[i];
    EXPECT_NEAR(v.x, 0.5 - 1.0 + 4.0 * (x.y - 2.0) / 12.0, 1e-14);
    EXPECT_EQ(v.y, 0.0);
    EXPECT_EQ(v.z, 0.0);
    spread = std::max(spread, std::fabs(v.x - s.particles.velocity[0].x));
  }
  EXPECT_GT(spread, 1.0);  // the lattice spans most of the gap
}

// Listing COL007's seventh-order fit: 0.2018 at the floor, 1 at the top particle, every particle
// between them scaled from initial_velocity. The listing's coefficients sum to 1.000132, the fit's
// own error at the top: hence 2e-4.
TEST(InitialFlow, CampbellsChuteFitRunsFromTheSlipToTheTopSpeed) {
  const CaseConfig c = load_case_from_string(discs_between_walls("campbell_chute"), "chute.toml");
  const InitialFlow flow(c, 10.0);
  EXPECT_NEAR(flow.at({0.0, 2.0, 0.0}).x, 0.5 * 0.2018029, 1e-15);
  EXPECT_NEAR(flow.at({0.0, 12.0, 0.0}).x, 0.5, 0.5 * 2e-4);
  EXPECT_NEAR(flow.at({0.0, 40.0, 0.0}).x, 0.5, 0.5 * 2e-4);  // above H: clamped to the top
  const dem::DemState s = dem::build_dem_state(c);
  double top = 0.0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) top = std::max(top, s.particles.position[i].y);
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    if (s.particles.position[i].y == top) {
      EXPECT_NEAR(s.particles.velocity[i].x, 0.5, 0.5 * 2e-4);
    }
}

// Lees-Edwards: the homogeneous shear u_x = rate (y - y_mid) on top of initial_velocity.
TEST(InitialFlow, LeesEdwardsShearIsZeroAtMidHeight) {
  std::string text = discs_between_walls("uniform");
  text.replace(text.find("y = \"wall\""), 10, "y = \"periodic\"");
  text.erase(text.find("[walls.ylo]"));  // no walls in unbounded shear
  text += "[lees_edwards]\nshear_rate = 0.25\n[run]\nduration = 1.0\n";
  const CaseConfig c = load_case_from_string(text, "sheared.toml");
  const InitialFlow flow(c, 0.0);
  EXPECT_DOUBLE_EQ(flow.at({3.0, 8.0, 0.0}).x, 0.5);
  EXPECT_DOUBLE_EQ(flow.at({3.0, 12.0, 0.0}).x, 0.5 + 0.25 * 4.0);
  EXPECT_DOUBLE_EQ(flow.at({3.0, 2.0, 0.0}).x, 0.5 - 0.25 * 6.0);
}
