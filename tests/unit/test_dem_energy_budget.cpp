// The soft-sphere engine's energy budget (engine_api/energy_budget.hpp): gravity's and the walls' work
// in, the change of kinetic + rotational + potential + elastic energy, and the dissipated energy,
// which the contacts' springs and dashpots took from the particles' relative motion and did not
// give back. Its value is checked against closed forms of binary impacts; the residual
// input - change - dissipated is the integrator's error (velocity Verlet against the trapezoidal
// rule for the forces' work), so it must shrink as dt^2.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <variant>

#include "grainflow/dem/engine_factory.hpp"
#include "test_support.hpp"

using namespace grainflow;

namespace {

// Two spheres (d = 2 mm, 2500 kg/m^3) meet head on at 0.4 m/s in a periodic box, no gravity.
std::string binary_case(const std::string& contact, const std::string& particles) {
  return R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.02, 0.02]
boundary = { x = "periodic", y = "periodic", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
[particles]
init = "file"
file = ")" +
         particles + R"("
[contact]
)" + contact +
         R"(
[run]
duration = 0.005
collision_steps = 50
)";
}

// `at_deepest`: the budget at the step of deepest overlap, where the pair stops approaching.
engine_api::EnergyBudget run_binary(const std::string& contact, double& kinetic_loss,
                                    engine_api::EnergyBudget* at_deepest = nullptr) {
  const test::ParticleFile file("pair.csv", "glass,0.004,0.01,0.01,0.2,0,0\nglass,0.0065,0.01,0.01,-0.2,0,0\n");
  const CaseConfig c = load_case_from_string(binary_case(contact, file.path()), "binary.toml");
  auto engine = test::engine_for(c, 1);
  return std::visit(
      [&](auto& e) {
        auto kinetic = [&] {
          double k = 0.0;
          for (std::size_t i = 0; i < e.state().particles.size(); ++i)
            k += engine_api::kinetic_energy(e.state().particles, i);
          return k;
        };
        const double before = kinetic();
        const long steps = std::lround(c.run.duration / e.state().time_step);
        const auto& p = e.state().particles;
        for (long k = 0; k < steps; ++k) {
          const double approach = p.velocity[0].x - p.velocity[1].x;
          e.step();
          if (at_deepest && approach > 0.0 && p.velocity[0].x - p.velocity[1].x <= 0.0) *at_deepest = e.energy_budget();
        }
        EXPECT_EQ(e.statistics().contacts, 0);  // apart again
        EXPECT_EQ(e.statistics().collisions, 1);
        kinetic_loss = before - kinetic();
        return e.energy_budget();
      },
      engine);
}

constexpr double kMass = 2500.0 * 4.0 / 3.0 * M_PI * 1e-9;  // kg, one sphere
constexpr double kApproach = 0.4;                           // m/s

// A damped linear spring: e = exp(-gamma_n t_c / 2), t_c = pi / sqrt(kn/m* - gamma_n^2/4), and the
// impact loses 1/2 m* v^2 (1 - e^2). 50 steps per contact resolve e to (pi/50)^2 ~ 0.4 %: 1 % covers
// it. The dissipated energy must also equal the kinetic energy the pair lost (no spring is loaded
// at the end) to the trapezoidal rule's error, again O(dt^2).
TEST(DemEnergyBudget, LinearDashpotImpactDissipatesTheClosedFormLoss) {
  const double kn = 1e4, gamma_n = 6000.0, m_eff = 0.5 * kMass;
  const double omega = std::sqrt(kn / m_eff - 0.25 * gamma_n * gamma_n);
  const double e = std::exp(-0.5 * gamma_n * M_PI / omega);
  double kinetic_loss = 0.0;
  const auto b = run_binary("model = \"linear_dashpot\"\nkn = 1.0e4\ngamma_n = 6000.0\nfriction = 0.0", kinetic_loss);
  const double loss = 0.5 * m_eff * kApproach * kApproach * (1.0 - e * e);
  EXPECT_NEAR(b.dissipated, loss, 0.01 * loss);
  EXPECT_NEAR(b.dissipated, kinetic_loss, 0.01 * loss);
  EXPECT_EQ(b.input(), 0.0);
  EXPECT_NEAR(b.residual(1.0), 0.0, 0.01);
}

// Walton-Braun: loading on K1, unloading on K2 = K1/e^2; the loop's area is 1 - e^2 of the impact
// energy exactly. The elastic energy it counts while touching (1/2 K2 (alpha - alpha0)^2) must make
// the loss right when it happens: at the deepest overlap the pair has put all its kinetic energy
// into the K1 line, 1/2 K1 alpha^2, of which K2 gives back e^2: the whole loss is already counted
// there (to the step's resolution, 1 / 50 of the contact: the kinetic energy left then is
// O((pi/50)^2) of it, 2 % covers it).
TEST(DemEnergyBudget, WaltonBraunImpactDissipatesOneMinusESquared) {
  const double e = 0.7, m_eff = 0.5 * kMass;
  double kinetic_loss = 0.0;
  engine_api::EnergyBudget deepest;
  const auto b =
      run_binary("model = \"walton_braun\"\nk1 = 1.0e4\nrestitution = 0.7\nfriction = 0.0", kinetic_loss, &deepest);
  const double loss = 0.5 * m_eff * kApproach * kApproach * (1.0 - e * e);
  EXPECT_NEAR(b.dissipated, loss, 0.01 * loss);
  EXPECT_NEAR(b.dissipated, kinetic_loss, 0.01 * loss);
  EXPECT_NEAR(deepest.dissipated, loss, 0.02 * loss);
}

// A bed of 100 frictional spheres poured by radius expansion and shaken by its floor (Gamma = 3.2):
// growth, the floor's work and gravity's potential all enter, and the budget must close to the
// integrator's error: measured 3.1e-5 (release build) and 8e-6 (debug build: other rounding, so
// another chaotic trajectory) at 15 steps a contact. 1e-3 bounds that, while a bookkeeping error
// (a missing work term) leaves a residual of order 1.
std::string shaken_bed(int collision_steps) {
  return R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.015, 0.06, 0.015]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.0, -9.81, 0.0]
[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 100
[particles]
init = "random"
region_hi = [0.015, 0.04, 0.015]
seed = 4
[contact]
model = "walton_braun"
k1 = 1.0e4
restitution = 0.9
friction = 0.5
[walls.ylo]
friction = 0.5
[drive]
face = "ylo"
amplitude = [0.0, 0.002, 0.0]
frequency = [0.0, 20.0, 0.0]
start = 0.1
ramp = 0.05
[run]
duration = 0.4
collision_steps = )" +
         std::to_string(collision_steps) + "\n";
}

engine_api::EnergyBudget run_bed(int collision_steps, const std::string& text = "") {
  const CaseConfig c = load_case_from_string(text.empty() ? shaken_bed(collision_steps) : text, "bed.toml");
  auto engine = test::engine_for(c, 1);
  return std::visit(
      [&](auto& e) {
        const long steps = std::lround(c.run.duration / e.state().time_step);
        for (long k = 0; k < steps; ++k) e.step();
        return e.energy_budget();
      },
      engine);
}

TEST(DemEnergyBudget, ClosesInAShakenBed) {
  const auto b = run_bed(15);
  EXPECT_GT(b.wall_work, 0.0);
  EXPECT_GT(b.growth_work, 0.0);
  EXPECT_GT(b.dissipated, 0.0);
  RecordProperty("residual", std::to_string(b.residual(1.0)));
  EXPECT_LT(std::fabs(b.residual(1.0)), 1e-3);
}

// The same bed with adhesion (JKR, Bond number F_c / m g ~ 0.2) and rolling resistance (epsd,
// mu_r = 0.1): the adhesive forces and the rolling couples act through the same force and torque
// arrays whose power the budget integrates, so it closes as tightly (measured 4.1e-5); a rolling
// torque applied outside them would leave its work, of the order of the dissipation, unbooked. (The
// residual does not see the springs' energy, which enters the change and the dissipation alike:
// test_jkr and test_rolling_resistance check those potentials against their forces.)
TEST(DemEnergyBudget, ClosesWithAdhesionAndRollingResistance) {
  std::string text = shaken_bed(15);
  const std::string law = "model = \"walton_braun\"\nk1 = 1.0e4\nrestitution = 0.9\n";
  ASSERT_NE(text.find(law), std::string::npos);
  text.replace(text.find(law), law.size(),
               "model = \"jkr\"\nrestitution = 0.9\nsurface_energy = 0.01\nrolling_friction = 0.1\n");
  const std::string species = "count = 100\n";
  text.replace(text.find(species), species.size(), species + "youngs_modulus = 5.0e6\npoisson_ratio = 0.3\n");
  const auto b = run_bed(15, text);
  EXPECT_GT(b.wall_work, 0.0);
  EXPECT_GT(b.dissipated, 0.0);
  RecordProperty("residual", std::to_string(b.residual(1.0)));
  EXPECT_LT(std::fabs(b.residual(1.0)), 1e-3);
}

// The same bed on a shaken bumpy floor (half-spheres of the grains' size, one diameter apart): the
// bumps ride with the floor and push the grains through the pair loop, so the floor's work is the
// bumps' (booked as the walls' work), and the budget closes as tightly as on a flat floor. Leaving
// the bumps' work out would leave a residual of the order of the whole input.
TEST(DemEnergyBudget, ClosesOnAShakenBumpyFloor) {
  std::string text = shaken_bed(15);
  const std::string faces = "y = [\"wall\", \"open\"]", floor = "[walls.ylo]\nfriction = 0.5\n";
  ASSERT_NE(text.find(faces), std::string::npos);
  text.replace(text.find(faces), faces.size(), "y = [\"bumpy\", \"open\"]");
  text.replace(text.find(floor), floor.size(), floor + "bump_diameter = 0.003\nspacing = 0.003\n");
  const auto b = run_bed(15, text);
  EXPECT_GT(b.wall_work, 0.0);
  EXPECT_GT(b.growth_work, 0.0);
  EXPECT_GT(b.dissipated, 0.0);
  RecordProperty("residual", std::to_string(b.residual(1.0)));
  EXPECT_LT(std::fabs(b.residual(1.0)), 1e-3);
}

// The residual is the integrator's alone: velocity Verlet's kinetic energy and the trapezoidal
// rule's work differ by -dt/4 (v1 - v0).(F1 - F0) a step, and over a smooth contact those
// differences cancel (gravity's telescope to dt^2/4 g (F_end - F_start)). One frictional sphere
// with spin bouncing on a shaken floor, its every work term present (gravity, the floor's, the
// contact's and the springs'): the budget closes to round-off, measured below 1e-12 of the input
// at 15 and 30 steps a contact. 1e-9 bounds that; the floor's work missing would leave all of it.
engine_api::EnergyBudget bouncing_sphere(int collision_steps) {
  const test::ParticleFile file("one.csv", "glass,0.005,0.004,0.005,0.05,0,0,0,0,40\n",
                                "species,x,y,z,vx,vy,vz,wx,wy,wz");
  const std::string text = R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.01, 0.05, 0.01]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.0, -9.81, 0.0]
[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
[particles]
init = "file"
file = ")" + file.path() + R"("
[contact]
model = "walton_braun"
k1 = 1.0e4
restitution = 0.8
friction = 0.5
[walls.ylo]
friction = 0.5
[drive]
face = "ylo"
amplitude = [0.0, 0.001, 0.0]
frequency = [0.0, 20.0, 0.0]
[run]
duration = 0.2
collision_steps = )" + std::to_string(collision_steps) +
                           "\n";
  const CaseConfig c = load_case_from_string(text, "bounce.toml");
  auto engine = test::engine_for(c, 1);
  return std::visit(
      [&](auto& e) {
        const long steps = std::lround(c.run.duration / e.state().time_step);
        for (long k = 0; k < steps; ++k) e.step();
        EXPECT_GT(e.statistics().wall_collisions, 3);
        return e.energy_budget();
      },
      engine);
}

TEST(DemEnergyBudget, ClosesForABouncingSphereToTheIntegratorsError) {
  for (const int steps : {15, 30}) {
    const auto b = bouncing_sphere(steps);
    EXPECT_GT(b.wall_work, 0.0) << steps;
    EXPECT_GT(b.dissipated, 0.0) << steps;
    EXPECT_LT(std::fabs(b.residual(1.0)), 1e-9) << steps << " steps a contact";
  }
}

}  // namespace
