// The pressure servo with soft particles (Campbell 1982 section 2.14.3, listing COL002, as the
// event-driven engine runs it). One sphere of unit mass rests under gravity on the bottom wall of a
// Couette cell whose top wall is far above: the wall's load is then the sphere's weight plus its
// momentum change, m g tau + m dv, exactly (velocity Verlet changes a momentum by the trapezoidal
// rule's impulse, which is how the servo integrates the load), so every update's measured stress
// is known to round-off. With it the wall speed follows the listing's rule, converging to
// 2 (sigma - sigma_target) in Campbell's units, the gap closes linearly between updates, and the
// energy budget books the walls' work of lifting the sphere.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "grainflow/config/couette_servo_rule.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

constexpr double kGravity = 10.0, kMass = 1.0, kWidth = 2.0, kTarget = 2.0;  // m/s^2, kg, m, Pa

std::string resting_sphere_case(const std::string& file, const std::string& servo_extra = "") {
  return R"([engine]
kind = "dem"
[domain]
lo = [0.0, 0.0, 0.0]
hi = [2.0, 10.0, 2.0]
boundary = { x = "periodic", y = "wall", z = "periodic" }
[gravity]
vector = [0.0, -10.0, 0.0]
[[species]]
name = "ball"
diameter = 1.0
density = 1.909859317102744
[particles]
init = "file"
file = ")" +
         file + R"("
[contact]
model = "linear_dashpot"
kn = 1.0e5
gamma_n = 60.0
friction = 0.5
[walls.yhi]
velocity = [1.0, 0.0, 0.0]
[servo]
normal_stress = 2.0
keep_shear_rate = false
scale_width = false
interval = 0.02
)" + servo_extra +
         R"(
[run]
duration = 3.0
)";
}

}  // namespace

TEST(DemCouetteServo, MeasuresTheWallsImpulseAndSteersTheWallsByTheListingsRule) {
  test::ParticleFile file("resting.csv", "ball,1.0,0.5,1.0,0.0,0.0,0.0\n");  // touching the floor, at rest
  const CaseConfig c = load_case_from_string(resting_sphere_case(file.path()), "servo.toml");
  DemEngineVariant variant = test::engine_for(c, 1);
  auto& e = std::get<DemEngine<LinearDashpot>>(variant);
  const CouetteServoRule& rule = e.state().servo;
  // Campbell's units: U = 1 m/s, m U^2 / R^3 = 8 Pa; updates every 3 contacts begun (none here),
  // 0.05 m of gap change or 0.02 s.
  ASSERT_DOUBLE_EQ(rule.speed_unit, 1.0);
  ASSERT_DOUBLE_EQ(rule.stress_unit, 8.0);
  ASSERT_DOUBLE_EQ(rule.config.gap_change, 0.05);
  const double area = kWidth * kWidth;
  const double dt = e.state().time_step;

  double since = 0.0, v_since = 0.0, speed = 0.0, gap_since = e.servo().gap(e.state());
  long long updates = 0;
  const long steps = std::lround(c.run.duration / dt);
  for (long k = 0; k < steps && !HasFailure(); ++k) {
    e.step();
    const double t = e.state().time;
    const double vy = e.state().particles.velocity[0].y;
    const CouetteServoState& s = e.servo().state();
    if (e.servo().updates() == updates) {
      // Between updates both walls move at +-speed: the gap changes linearly.
      EXPECT_NEAR(e.servo().gap(e.state()), gap_since + 2.0 * speed * (t - since), 1e-12) << "t = " << t;
      continue;
    }
    ++updates;
    // The sphere's momentum balance over the period: the floor's impulse is m g tau + m dv.
    const double impulse = 2.0 * s.measured_stress * (t - since) * area;  // measured: (J_bottom + J_top) / 2 / (tau A)
    const double expected = kMass * kGravity * (t - since) + kMass * (vy - v_since);
    EXPECT_NEAR(impulse, expected, 1e-10 * expected) << "update " << updates;
    EXPECT_NEAR(s.wall_speed, rule.wall_speed(speed, s.measured_stress), 1e-15);
    EXPECT_NEAR(s.gap, gap_since + 2.0 * speed * (t - since), 1e-12);
    since = t, v_since = vy, speed = s.wall_speed, gap_since = s.gap;
  }
  // Steady, the floor carries the weight, sigma = m g / (2 A) = 1.25 Pa (the top wall nothing), and
  // v = v/2 + (sigma - sigma_target) has its fixed point 2 (1.25 - 2) / 8 U = -0.1875 m/s: the gap
  // closes. The sphere rides the rising floor; each speed change kicks it, and these kicks decay
  // with the speed's changes (halved at each update), so 1e-3 after some 40 updates.
  EXPECT_GT(updates, 100);
  EXPECT_NEAR(speed, 2.0 * (kMass * kGravity / (2.0 * area) - kTarget) / rule.stress_unit * rule.speed_unit,
              1e-3 * 0.1875);
  // The energy budget: the floor's work lifts the sphere and sets it moving (m g dh + m v^2 / 2,
  // ~5.6 J), and a little more goes into the kicks' damping and the spring: at most
  // m/2 sum dv^2 = m/2 (0.094^2 + 0.047^2 + ...) = 0.006 J, and m g delta / 2 = 5e-4 J. The budget
  // closes to the integrator's error.
  const engine_api::EnergyBudget b = e.energy_budget();
  const double lift = e.state().particles.position[0].y - 0.5;
  const double v = e.state().particles.velocity[0].y;
  const double raised = kMass * kGravity * lift + 0.5 * kMass * v * v;
  EXPECT_GT(lift, 0.3);
  EXPECT_GT(b.wall_work, raised);
  EXPECT_LT(b.wall_work - raised, 0.01);
  EXPECT_LT(std::fabs(b.residual(1.0)), 1e-6);
}

TEST(DemCouetteServo, RefusesWhatItCannotDo) {
  test::ParticleFile file("resting.csv", "ball,1.0,0.5,1.0,0.0,0.0,0.0\n");
  auto refused = [&](const std::string& text, const std::string& key) {
    try {
      load_case_from_string(text, "servo.toml");
      ADD_FAILURE() << "accepted: " << key;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(key), std::string::npos) << error.what();
    }
  };
  std::string widths = resting_sphere_case(file.path());
  widths.replace(widths.find("scale_width = false"), 19, "scale_width = true");
  refused(widths, "servo.scale_width");
  std::string pushed = resting_sphere_case(file.path());
  pushed.replace(pushed.find("velocity = [1.0, 0.0, 0.0]"), 26, "velocity = [1.0, 0.1, 0.0]");
  refused(pushed, "walls.yhi.velocity");
  std::string resting = resting_sphere_case(file.path());
  resting.replace(resting.find("velocity = [1.0, 0.0, 0.0]"), 26, "velocity = [0.0, 0.0, 0.0]");
  refused(resting, "walls.yhi.velocity");
}
