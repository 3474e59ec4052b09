// Campbell's Couette servo (listing COL002) on its own: the wall speed it sets from measured wall
// impulses, the walls' motion, the shear rate and the width law, against the listing's formulas.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "grainflow/edmd/couette_servo.hpp"
#include "grainflow/run/case_loader.hpp"

using namespace grainflow;
using namespace grainflow::edmd;

namespace {

const char* kCell = R"(
[engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [9.6, 24.0, 1.0]
boundary = { x = "periodic", y = "wall", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "disc"
diameter = 2.0
density = 0.3183098861837907
count = 40
[particles]
init = "lattice"
lattice_spacing = 1.2
[collision]
restitution = 0.6
[walls.ylo]
condition = "rough"
[walls.yhi]
condition = "rough"
velocity = [1.0, 0.0, 0.0]
[servo]
normal_stress = 1e-3
[run]
duration = 100.0
)";

}  // namespace

TEST(CouetteServo, StartsFromTheCellsGeometry) {
  const EdmdState s = build_edmd_state(load_case_from_string(kCell, "servo.toml"));
  const CouetteServo servo(s);
  EXPECT_DOUBLE_EQ(servo.gap_at(s, 0.0), 24.0);
  EXPECT_DOUBLE_EQ(servo.state().gap, 24.0);
  EXPECT_DOUBLE_EQ(servo.state().width, 9.6);
  EXPECT_DOUBLE_EQ(servo.state().top_speed, 1.0);
  EXPECT_EQ(servo.width_rate(), 0.0);
  EXPECT_DOUBLE_EQ(servo.width_at(50.0), 9.6);
}

// Listing COL002 in Campbell's units: v' = v/2 + (sigma_measured - sigma_target), clipped to
// +-sigma_target; both walls move at v' (apart when the cell is over-pressed), the walls keep
// U_T / H = 1/24, the width grows at aspect x 2 v'. Then impulses count afresh. The shear rate is
// kept by the top wall alone (the listing, "top") or by both symmetrically about their mean speed,
// U_T / 2 = 0.5 here ("both"); "top" is the default.
class CouetteServoWalls : public testing::TestWithParam<const char*> {};
INSTANTIATE_TEST_SUITE_P(ShearRateWalls, CouetteServoWalls, testing::Values("both", "top"));

TEST_P(CouetteServoWalls, UpdateFollowsListingCol002) {
  const std::string walls = GetParam();
  EdmdState s =
      build_edmd_state(load_case_from_string(kCell, "servo.toml", {"servo.shear_rate_walls=\"" + walls + "\""}));
  CouetteServo servo(s);
  const double target = s.servo.normal_stress / s.stress_unit;
  for (const double measured_over_target : {1.5, 0.9, 20.0}) {
    const double span = 2.0;
    s.time += span;
    const double stress = measured_over_target * s.servo.normal_stress;  // what the walls should report
    const double impulse = stress * span * s.box.length(0);
    servo.add_normal_impulse(0, impulse);
    servo.add_normal_impulse(1, impulse);
    const double previous = servo.state().wall_speed;
    ASSERT_TRUE(servo.measure(s, 2));
    const double gap_before = servo.gap_at(s, s.time);
    ASSERT_TRUE(servo.move_walls(s));
    servo.finish_update(s, 0);
    const double expected =
        std::clamp(0.5 * previous / s.speed_unit + (stress / s.stress_unit - target), -target, target) * s.speed_unit;
    EXPECT_NEAR(servo.state().wall_speed, expected, 1e-12 * (std::fabs(expected) + s.speed_unit));
    EXPECT_NEAR(servo.state().measured_stress, stress, 1e-12 * stress);
    EXPECT_DOUBLE_EQ(servo.state().gap, gap_before);
    const auto bottom = std::find_if(s.walls.begin(), s.walls.end(), [](const EdmdWall& w) { return w.face == 2; });
    const auto top = std::find_if(s.walls.begin(), s.walls.end(), [](const EdmdWall& w) { return w.face == 3; });
    EXPECT_DOUBLE_EQ(bottom->velocity.y, -expected);
    EXPECT_DOUBLE_EQ(top->velocity.y, expected);
    EXPECT_NEAR(top->velocity.x - bottom->velocity.x, gap_before / 24.0, 1e-12);  // U_T / H kept
    if (walls == "top") EXPECT_EQ(bottom->velocity.x, 0.0);
    else EXPECT_NEAR(0.5 * (top->velocity.x + bottom->velocity.x), 0.5, 1e-12);
    EXPECT_NEAR(servo.width_rate(), 9.6 / 24.0 * 2.0 * expected, 1e-15);
    if (measured_over_target == 20.0) {
      EXPECT_DOUBLE_EQ(expected, target * s.speed_unit);  // clipped
    }
  }
  // Nothing to measure without time passing.
  EXPECT_FALSE(servo.measure(s, 2));
}
