// Rolling resistance (Ai, Chen, Rotter & Ooi 2011): the torque's closed forms, and through the
// engine the rigid-body mechanics it implies for a sphere on a plane. With the torque capped at
// mu_r R* F_n (R* = r on a wall), a sphere on a slope of angle theta
//   - stays put when tan(theta) <= mu_r (the cap balances friction's torque: m g sin r <= mu_r r N),
//     which only the spring model (epsd) can do: the constant torque flips with every step's spin;
//   - otherwise rolls without slipping at a = (5/7) g (sin(theta) - mu_r cos(theta)), both models
//     ((I/r^2) a = F_t - mu_r N, m a = m g sin - F_t, I = 2/5 m r^2);
// and on a flat floor a rolling sphere stops in v0 / ((5/7) mu_r g) and stays stopped (epsd).
// The rolling torque is a couple, so two spinning spheres meeting keep their total angular momentum.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <variant>

#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/rolling_resistance.hpp"
#include "dem_incline_case.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

// ---- the torque alone ----

RollingKinematics kinematics(const Vec3& spin, double normal_force) {
  RollingKinematics k;
  k.normal = {0.0, 1.0, 0.0};
  k.relative_spin = spin;
  k.effective_radius = 1e-3;
  k.rolling_inertia = 1e-11;
  k.normal_force = normal_force;
  return k;
}

TEST(RollingTorque, ConstantTorqueOpposesTheRollingAtItsCap) {
  RollingParams p;
  p.model = RollingModel::constant_torque;
  p.friction = 0.2;
  RollingState s;
  // Spin about the normal (twisting) is no rolling: only the tangential part is resisted.
  const Vec3 m = RollingResistance::torque(p, s, kinematics({3.0, 50.0, -4.0}, 2.0), 1e-6);
  const double cap = 0.2 * 1e-3 * 2.0;
  EXPECT_NEAR(m.x, -cap * 3.0 / 5.0, 1e-15);
  EXPECT_NEAR(m.z, cap * 4.0 / 5.0, 1e-15);
  EXPECT_EQ(m.y, 0.0);
  // A pull (negative normal force) carries no rolling load; no rolling, no torque.
  EXPECT_EQ(norm(RollingResistance::torque(p, s, kinematics({3.0, 0.0, 0.0}, -1.0), 1e-6)), 0.0);
  EXPECT_EQ(norm(RollingResistance::torque(p, s, kinematics({0.0, 7.0, 0.0}, 1.0), 1e-6)), 0.0);
}

TEST(RollingTorque, EpsdSpringLoadsElasticallyThenSlidesAtTheCapAndUnloadsElastically) {
  RollingParams p;
  p.model = RollingModel::epsd;
  p.friction = 0.2;
  p.damping = 0.0;                                   // the spring alone
  p.stiffness_per_radius2 = 2.25 * 1e4 * 0.2 * 0.2;  // c_k k_n mu_r^2 with k_n = 1e4 N/m
  const double kr = p.stiffness_per_radius2 * 1e-6;  // N m/rad at R* = 1 mm
  const double cap = 0.2 * 1e-3 * 2.0;               // N m at F_n = 2 N
  RollingState s;
  const double dt = 1e-3, w = 10.0;  // rad/s about x: theta grows by 0.01 rad a step
  // Elastic: M = -k_r theta while k_r theta < cap (cap / k_r = 0.44 rad = 44 steps).
  for (int step = 1; step <= 40; ++step) {
    const Vec3 m = RollingResistance::torque(p, s, kinematics({w, 0.0, 0.0}, 2.0), dt);
    EXPECT_NEAR(m.x, -kr * w * dt * step, 1e-12 * cap);
  }
  EXPECT_NEAR(RollingResistance::elastic_energy(p, s, 1e-3), 0.5 * kr * std::pow(w * dt * 40, 2), 1e-12 * cap);
  // Past the cap: held there (plastic rolling), whatever the further rotation.
  for (int step = 41; step <= 200; ++step) RollingResistance::torque(p, s, kinematics({w, 0.0, 0.0}, 2.0), dt);
  EXPECT_NEAR(s.spring.x, -cap, 1e-15);
  // Rolling back unloads along the elastic line from the cap: hysteresis, not a reset.
  const Vec3 back = RollingResistance::torque(p, s, kinematics({-w, 0.0, 0.0}, 2.0), 10 * dt);
  EXPECT_NEAR(back.x, -cap + kr * w * 10 * dt, 1e-12 * cap);
  // A smaller load lowers the cap at once.
  const Vec3 unloaded = RollingResistance::torque(p, s, kinematics({0.0, 0.0, 0.0}, 0.5), dt);
  EXPECT_NEAR(unloaded.x, -0.25 * cap, 1e-15);
}

TEST(RollingTorque, EpsdDashpotActsBelowTheCapOnly) {
  RollingParams p;
  p.model = RollingModel::epsd;
  p.friction = 0.2;
  p.damping = 0.3;
  p.stiffness_per_radius2 = 9e2;
  const RollingKinematics k = kinematics({0.0, 0.0, 2.0}, 2.0);
  const double kr = p.stiffness_per_radius2 * 1e-6;
  RollingState s;
  // First step from rest, elastic: spring -k_r w dt plus dashpot -eta 2 sqrt(I_r k_r) w.
  const Vec3 m = RollingResistance::torque(p, s, k, 1e-6);
  EXPECT_NEAR(m.z, -kr * 2.0 * 1e-6 - 0.3 * 2.0 * std::sqrt(1e-11 * kr) * 2.0, 1e-18);
  // At the cap the dashpot is off (Ai et al.'s f = 0): the torque is the cap exactly.
  const Vec3 full = RollingResistance::torque(p, s, k, 1.0);
  EXPECT_NEAR(full.z, -0.2 * 1e-3 * 2.0, 1e-15);
}

TEST(RollingTorque, EpsdSpringTurnsWithTheContactKeepingItsSize) {
  RollingParams p;
  p.model = RollingModel::epsd;
  p.friction = 0.5;
  p.stiffness_per_radius2 = 1e3;
  RollingState s;
  s.spring = {3e-4, 0.0, 0.0};
  RollingKinematics k = kinematics({}, 10.0);
  const double tilt = 0.1;
  k.normal = {std::sin(tilt), std::cos(tilt), 0.0};  // the contact turned about z
  const Vec3 m = RollingResistance::torque(p, s, k, 1e-6);
  EXPECT_NEAR(dot(s.spring, k.normal), 0.0, 1e-18);
  EXPECT_NEAR(norm(s.spring), 3e-4, 1e-18);
  EXPECT_NEAR(norm(m), 3e-4, 1e-18);
}

// ---- a sphere on a plane, through the engine ----

constexpr double kG = 9.81;  // m/s^2
constexpr double kDiameter = 0.002;
constexpr double kDensity = 2500.0;
constexpr double kMu = 0.5;   // sliding friction on the floor: never reached here
constexpr double kMuR = 0.1;  // rolling friction

struct Motion {
  double displacement = 0.0;      // m along x
  double velocity = 0.0;          // m/s along x at the end
  double angular_velocity = 0.0;  // rad/s about z at the end
  double time = 0.0;
  double radius = 0.0;
};

// One sphere on the ylo wall, gravity tilted by theta down +x, starting with speed v0 along x and
// the spin of rolling without slip; observed at `at` seconds (each entry of the result).
std::vector<Motion> run_sphere(const std::string& law, const std::string& model, double theta, double v0,
                               const std::vector<double>& at) {
  const double r = 0.5 * kDiameter;
  const double mass = M_PI / 6.0 * kDiameter * kDiameter * kDiameter * kDensity;
  const double y0 = r - mass * kG * std::cos(theta) / 1.0e4;  // pressed in by its static overlap
  std::ostringstream row;
  row.precision(17);
  row << "glass,0.01," << y0 << ",0.01," << v0 << ",0,0,0,0," << -v0 / r << "\n";
  const test::ParticleFile csv("rolling.csv", row.str(), "species,x,y,z,vx,vy,vz,wx,wy,wz");
  const std::string contact = law == "walton_braun" ? "model = \"walton_braun\"\nk1 = 1.0e4\nrestitution = 0.9\n"
                                                    : "model = \"linear_dashpot\"\nkn = 1.0e4\ngamma_n = 500.0\n";
  const std::string text = test::dem_incline_case(
      kG, theta, csv.path(), contact + "friction = 0.5\nrolling_model = \"" + model + "\"\nrolling_friction = 0.1\n");
  auto engine = test::engine_from_toml(text, testing::TempDir() + "rolling.toml", 1);
  std::vector<Motion> out;
  std::visit(
      [&](auto& e) {
        EXPECT_TRUE(e.rolling_resistance);
        const auto& p = e.state().particles;
        const double x0 = e.unwrapped_position(0).x;
        for (double t : at) {
          while (e.state().time < t) e.step();
          out.push_back(
              {e.unwrapped_position(0).x - x0, p.velocity[0].x, p.angular_velocity[0].z, e.state().time, p.radius[0]});
        }
      },
      engine);
  return out;
}

// Tolerances: Verlet integrates constant accelerations exactly. The start is not steady: the
// tangential spring must stretch and the epsd spring turn (by cap / k_r ~ 5e-5 rad) before they
// carry their loads, and a fresh epsd contact's first evaluation (no time passed, spring still
// zero) applies the full dashpot to a sphere set down rolling: measured, the speed then drops by
// 5.6e-4 m/s in the first step. So the tests difference two times after the start, when only the
// springs' small undamped ringing (< 1e-6 m/s) is left. The torque's lever is r, not r - delta
// (delta / r ~ 1e-5). 1e-3 is far above those and far below a wrong cap (R* = r/2 on a wall would
// halve the deceleration) or a missing 5/7 (40%).
class RollingOnAPlane : public testing::TestWithParam<std::tuple<std::string, std::string>> {};

// The motion between two times once rolling is steady: x2 - x1 = v1 T + a T^2 / 2, v2 - v1 = a T.
void expect_constant_acceleration(const Motion& m1, const Motion& m2, double a, const std::string& what) {
  const double T = m2.time - m1.time;
  const double travel = m1.velocity * T + 0.5 * a * T * T;
  EXPECT_NEAR(m2.velocity - m1.velocity, a * T, 1e-3 * std::fabs(a) * T) << what;
  EXPECT_NEAR(m2.displacement - m1.displacement, travel, 1e-3 * std::fabs(travel)) << what;
  EXPECT_NEAR(m2.velocity + m2.radius * m2.angular_velocity, 0.0, 1e-3 * std::fabs(a) * T) << what << ": slipped";
}

TEST_P(RollingOnAPlane, RollsDownSteeperSlopesAtFiveSeventhsOfTheNetDrive) {
  const auto& [law, model] = GetParam();
  for (double ratio : {2.0, 4.0}) {  // tan(theta) / mu_r
    const double theta = std::atan(ratio * kMuR);
    const std::vector<Motion> m = run_sphere(law, model, theta, 0.0, {0.01, 0.05});
    const double a = 5.0 / 7.0 * kG * (std::sin(theta) - kMuR * std::cos(theta));
    expect_constant_acceleration(m[0], m[1], a, "tan = " + std::to_string(ratio) + " mu_r");
  }
}

TEST_P(RollingOnAPlane, DeceleratesOnTheFlatAtFiveSeventhsMuRG) {
  const auto& [law, model] = GetParam();
  const double v0 = 0.1;  // m/s: stops after v0 / a = 0.143 s
  const double a = 5.0 / 7.0 * kMuR * kG;
  const std::vector<Motion> m = run_sphere(law, model, 0.0, v0, {0.02, 0.1});
  expect_constant_acceleration(m[0], m[1], -a, "flat");
}

INSTANTIATE_TEST_SUITE_P(LawsAndModels, RollingOnAPlane,
                         testing::Combine(testing::Values("walton_braun", "linear_dashpot"),
                                          testing::Values("constant_torque", "epsd")));

// The spring holds: below tan(theta) = mu_r a sphere set down at rest stays (it creeps by the
// spring's elastic turn, cap / k_r r ~ 5e-8 m, and no more), and a sphere rolling on the flat stops
// at v0^2 / (2 a) and stays there.
TEST(RollingResistanceEpsd, HoldsASphereOnASlopeBelowTheRollingAngle) {
  for (double ratio : {0.5, 0.9}) {
    const double theta = std::atan(ratio * kMuR);
    const std::vector<Motion> m = run_sphere("linear_dashpot", "epsd", theta, 0.0, {0.05, 0.2});
    EXPECT_LT(std::fabs(m[1].displacement), 1e-6 * kDiameter * 100) << "tan = " << ratio << " mu_r";
    EXPECT_LT(std::fabs(m[1].displacement - m[0].displacement), 1e-7) << "still creeping";
    // Free, it would have rolled (5/14) g sin(theta) t^2 = 7e-4 m or more by now.
    EXPECT_LT(std::fabs(m[1].velocity), 1e-5);
  }
}

TEST(RollingResistanceEpsd, StopsARollingSphereAndKeepsItStopped) {
  const double v0 = 0.1, a = 5.0 / 7.0 * kMuR * kG;
  const double stop = v0 / a;
  const std::vector<Motion> m = run_sphere("linear_dashpot", "epsd", 0.0, v0, {0.02, stop + 0.05, stop + 0.3});
  const double distance = m[0].velocity * m[0].velocity / (2.0 * a);  // from t = 0.02 on (the start aside)
  EXPECT_NEAR(m[1].displacement - m[0].displacement, distance, 1e-3 * distance);
  EXPECT_NEAR(m[2].displacement, m[1].displacement, 1e-6 * distance);
  EXPECT_LT(std::fabs(m[2].velocity), 1e-6 * v0);
  EXPECT_LT(std::fabs(m[2].angular_velocity * m[2].radius), 1e-6 * v0);
}

// Two spheres with different spins meet off-centre in free space, without sliding friction (whose
// torque, levered at r_i + r_j rather than the centres' distance, keeps angular momentum only to
// O(overlap / r)): rolling resistance alone changes their spins, and as a couple it keeps their
// total angular momentum about the origin, orbital plus spin, to round-off, as velocity Verlet does
// for central forces; linear momentum too.
TEST(RollingResistanceCouple, KeepsTotalAngularMomentum) {
  const test::ParticleFile csv("couple.csv",
                               "glass,0.010,0.0100,0.01,0.05,0,0,30,-20,40\n"
                               "glass,0.012,0.0105,0.01,-0.05,0,0,-50,10,0\n",
                               "species,x,y,z,vx,vy,vz,wx,wy,wz");
  for (const char* model : {"constant_torque", "epsd"}) {
    const std::string text = R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.03, 0.03, 0.03]
boundary = { x = "open", y = "open", z = "open" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
[particles]
init = "file"
file = ")" + csv.path() + R"("
[contact]
model = "linear_dashpot"
kn = 1.0e4
gamma_n = 500.0
friction = 0.0
rolling_friction = 0.3
rolling_model = ")" + std::string(model) +
                             R"("
[run]
duration = 1.0
)";
    auto engine = test::engine_from_toml(text, testing::TempDir() + "couple.toml", 1);
    std::visit(
        [&](auto& e) {
          const auto& p = e.state().particles;
          double scale = 0.0;  // kg m/s, the momenta's sizes: round-off is relative to them
          auto momentum = [&] {
            Vec3 linear, angular;
            scale = 0.0;
            for (std::size_t i = 0; i < p.size(); ++i) {
              linear += p.mass[i] * p.velocity[i];
              angular +=
                  p.mass[i] * cross(p.position[i], p.velocity[i]) + (1.0 / p.inv_inertia[i]) * p.angular_velocity[i];
              scale += p.mass[i] * norm(p.velocity[i]);
            }
            return std::pair{linear, angular};
          };
          const auto [linear0, angular0] = momentum();
          const Vec3 spin0 = p.angular_velocity[0];
          for (int k = 0; k < 4000; ++k) e.step();  // the contact lasts ~ pi sqrt(m / 2 kn) ~ 70 steps
          EXPECT_GT(e.statistics().collisions, 0) << model;
          EXPECT_GT(norm(p.angular_velocity[0] - spin0), 1.0) << model << ": the contact must change the spins";
          const auto [linear1, angular1] = momentum();
          // Velocity Verlet keeps momenta exactly for pairwise forces and couples: round-off only.
          EXPECT_NEAR(norm(linear1 - linear0), 0.0, 1e-13 * scale) << model;
          EXPECT_NEAR(norm(angular1 - angular0), 0.0, 1e-11 * norm(angular0)) << model;
        },
        engine);
  }
}

}  // namespace
