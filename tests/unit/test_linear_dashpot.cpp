// Linear spring-dashpot with tangential history (LAMMPS gran/hooke/history): a head-on impact run
// by the engine reproduces the closed-form restitution and contact duration; the tangential force
// respects the Coulomb limit and the stored shear displacement stays in the tangent plane.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <variant>

#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/linear_dashpot.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

struct Impact {
  double restitution = 0.0;  // separation / approach speed
  double duration = 0.0;     // s, between the zero crossings of the overlap
  double effective_mass = 0.0;
  double time_step = 0.0;  // s, as the engine chose it
  LinearDashpot::Params params;
};

// Two spheres (densities 2500 and 2500 * mass_ratio, d = 2 mm) meet head-on along x in a periodic
// box with no gravity; the engine integrates the impact at `steps` steps per reference contact.
Impact head_on(double gamma_n, double mass_ratio, double speed, int steps) {
  std::ostringstream rows;
  rows << "a,0.008,0.01,0.01," << 0.5 * speed << ",0,0\n";
  rows << "b,0.01000001,0.01,0.01," << -0.5 * speed << ",0,0\n";
  const test::ParticleFile csv("dashpot_head_on.csv", rows.str());
  char text[2048];
  std::snprintf(text, sizeof text, R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.02, 0.02]
boundary = { x = "periodic", y = "periodic", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "a"
diameter = 0.002
density = 2500.0
[[species]]
name = "b"
diameter = 0.002
density = %.17g
[particles]
init = "file"
file = "%s"
[contact]
model = "linear_dashpot"
kn = 1.0e4
gamma_n = %.17g
[run]
duration = 1.0
collision_steps = %d
)",
                2500.0 * mass_ratio, csv.path().c_str(), gamma_n, steps);
  auto engine = test::engine_from_toml(text, testing::TempDir() + "dashpot.toml", 1);
  Impact out;
  std::visit(
      [&](auto& e) {
        auto& p = e.state().particles;
        const double dt = e.state().time_step;
        auto overlap = [&] {
          return p.radius[0] + p.radius[1] - norm(e.state().box.minimum_image(p.position[0], p.position[1]));
        };
        auto relative_speed = [&] { return std::fabs(p.velocity[0].x - p.velocity[1].x); };
        const double approach = relative_speed();
        double previous = overlap(), start = -1.0, end = -1.0;
        for (long k = 1; k < 1000000 && end < 0.0; ++k) {
          e.step();
          const double now = overlap();
          // Zero crossings by linear interpolation between steps: O(dt^2) in time.
          const double crossing = (k - 1 + previous / (previous - now)) * dt;
          if (start < 0.0 && previous <= 0.0 && now > 0.0) start = crossing;
          if (start >= 0.0 && previous > 0.0 && now <= 0.0) end = crossing;
          previous = now;
        }
        e.step();  // out of contact: velocities are final
        out.restitution = relative_speed() / approach;
        out.duration = end - start;
        out.effective_mass = 1.0 / (p.inv_mass[0] + p.inv_mass[1]);
        out.time_step = dt;
      },
      engine);
  out.params = {1.0e4, 0.0, gamma_n, 0.0, 0.0};
  return out;
}

}  // namespace

// Restitution and contact duration of a head-on impact, e = exp(-gamma_n t_c / 2) and
// t_c = pi / sqrt(kn/m_eff - gamma_n^2/4), for several damping rates, mass ratios and speeds.
// Tolerances: the dashpot force jumps by m_eff gamma_n |v_n| when the spheres touch and when they
// separate (LAMMPS' convention), and the engine places each jump only to within one step dt; the
// velocity error is then <= gamma_n dt |v_n| at each end, i.e. <= gamma_n dt (1 + e) / e relative
// on e, and <= gamma_n dt relative on t_c. On top of that velocity Verlet and the kink of the spring
// at zero overlap give errors of order (omega dt)^2 <= (pi / n)^2 (n = steps per contact). Measured
// errors are 2-5x below these bounds (e.g. 1.4e-3 against 4.0e-3 on e for gamma_n = 2000/s, n = 100).
TEST(LinearDashpot, HeadOnImpactMatchesClosedFormRestitutionAndDuration) {
  const double kn = 1.0e4;
  for (int steps : {50, 100}) {
    for (double gamma_n : {0.0, 200.0, 2000.0}) {
      for (double mass_ratio : {1.0, 4.0}) {
        for (double speed : {0.05, 1.0}) {
          const Impact i = head_on(gamma_n, mass_ratio, speed, steps);
          // Closed forms written out here, then checked against the law's own.
          const double omega = std::sqrt(kn / i.effective_mass - 0.25 * gamma_n * gamma_n);
          const double tc = M_PI / omega;
          const double e = std::exp(-0.5 * gamma_n * tc);
          const BinaryContact closed = LinearDashpot::binary_contact(i.params, {i.effective_mass, 0.0, 0.0});
          ASSERT_NEAR(closed.duration, tc, 1e-14 * tc);
          ASSERT_NEAR(closed.restitution, e, 1e-14);
          const double dt = i.time_step;
          const double second_order = (M_PI / steps) * (M_PI / steps);
          EXPECT_NEAR(i.restitution, e, e * (gamma_n * dt * (1.0 + e) / e + second_order))
              << "n=" << steps << " gamma_n=" << gamma_n << " m_b/m_a=" << mass_ratio << " v=" << speed;
          EXPECT_NEAR(i.duration, tc, tc * (gamma_n * dt + second_order))
              << "n=" << steps << " gamma_n=" << gamma_n << " m_b/m_a=" << mass_ratio << " v=" << speed;
        }
      }
    }
  }
}

namespace {

// kn = 1e4 N/m, kt = 2/7 kn, gamma_n = 1000/s, gamma_t = gamma_n / 2 (the loader's defaults), mu = 0.4.
constexpr LinearDashpot::Params kParams{1.0e4, 2.0 / 7.0 * 1.0e4, 1000.0, 500.0, 0.4};
constexpr double kMass = 5.0e-6;  // kg, effective

ContactKinematics kinematics(const Vec3& normal, double overlap, double normal_velocity, const Vec3& slip_velocity) {
  ContactKinematics c;
  c.normal = normal;
  c.overlap = overlap;
  c.normal_velocity = normal_velocity;
  c.slip_velocity = slip_velocity;
  c.effective_mass = kMass;
  return c;
}

}  // namespace

// Constant slip velocity u at constant overlap: the force is the linear spring plus dashpot,
// -(kt u t + m gamma_t u), until it reaches mu Fn; from then on it slides at exactly mu Fn against
// the slip. Both phases are closed forms, so only round-off is allowed.
TEST(LinearDashpot, ConstantSlipSticksLinearlyThenSlidesAtCoulombLimit) {
  LinearDashpot::State s;
  const double dt = 1.0e-6, u = 0.02;
  const double overlap = 1.0e-5;  // Fn = kn overlap = 0.1 N, mu Fn = 0.04 N
  const double limit = kParams.friction * kParams.kn * overlap;
  const double stick_steps = (limit / u - kMass * kParams.gamma_t) / (kParams.kt * dt);  // ~ 698
  int sliding_steps = 0;
  for (int k = 1; k <= 2000; ++k) {
    const auto f = LinearDashpot::force(kParams, s, kinematics({0, 0, 1}, overlap, 0.0, {u, 0, 0}), dt);
    ASSERT_DOUBLE_EQ(f.normal, kParams.kn * overlap);
    ASSERT_EQ(f.tangential.y, 0.0);
    ASSERT_EQ(f.tangential.z, 0.0);
    const double magnitude = std::fabs(f.tangential.x);
    ASSERT_LT(f.tangential.x, 0.0) << "friction must oppose the slip";
    ASSERT_LE(magnitude, limit * (1.0 + 1e-14)) << "Coulomb limit exceeded at step " << k;
    if (k < stick_steps) {
      EXPECT_NEAR(magnitude, kParams.kt * u * k * dt + kMass * kParams.gamma_t * u, 1e-12 * limit) << "step " << k;
    } else if (k > stick_steps + 1) {
      EXPECT_NEAR(magnitude, limit, 1e-14 * limit) << "step " << k;
      ++sliding_steps;
    }
  }
  EXPECT_GT(sliding_steps, 1000);
  // While sliding, LAMMPS' rescaling puts spring plus dashpot on the limit, so the spring alone
  // holds mu Fn - m_eff gamma_t u; that is the force left when the slip stops.
  const double spring = limit - kMass * kParams.gamma_t * u;
  EXPECT_NEAR(kParams.kt * norm(s.shear), spring, 1e-14 * limit);
  const auto f = LinearDashpot::force(kParams, s, kinematics({0, 0, 1}, overlap, 0.0, {}), dt);
  EXPECT_NEAR(-f.tangential.x, spring, 1e-14 * limit);
}

// Random contact histories (fixed seed): overlaps, approach and separation speeds (the damped
// normal force may turn attractive), slips, and a normal that rotates a little every step.
// Always |Ft| <= mu |Fn|; a trial force beyond the limit is scaled onto it without turning; the
// stored shear and Ft stay in the current tangent plane; and the force is the spring-dashpot of the
// stored shear, Ft = -(kt shear + m_eff gamma_t v_slip). All to round-off (1e-12 relative to the
// force or displacement scale).
TEST(LinearDashpot, CoulombLimitAndTangentPlaneHoldOnRandomHistories) {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random_vector = [&] { return Vec3{unit(rng), unit(rng), unit(rng)}; };
  int sliding = 0, sticking = 0, attractive = 0;
  for (int history = 0; history < 50; ++history) {
    LinearDashpot::State s;
    Vec3 normal = random_vector();
    normal *= 1.0 / norm(normal);
    for (int k = 0; k < 400; ++k) {
      // Rotate the normal by up to ~0.05 rad.
      Vec3 turned = normal + 0.05 * random_vector();
      normal = turned * (1.0 / norm(turned));
      Vec3 slip = 0.5 * random_vector();
      slip -= dot(slip, normal) * normal;                       // the engine's slip velocity is tangential
      const double overlap = 1.0e-5 * (0.5 + 0.5 * unit(rng));  // kn overlap = 0 .. 0.1 N
      const double normal_velocity = 5.0 * unit(rng);           // m_eff gamma_n |v_n| up to 0.025 N
      const double dt = 1.0e-6;
      // Trial (sticking) force from the previous shear, carried into the current plane.
      Vec3 trial_shear = s.shear + dt * slip;
      trial_shear -= dot(trial_shear, normal) * normal;
      const Vec3 trial = -(kParams.kt * trial_shear + (kMass * kParams.gamma_t) * slip);
      const auto f = LinearDashpot::force(kParams, s, kinematics(normal, overlap, normal_velocity, slip), dt);
      const double limit = kParams.friction * std::fabs(f.normal);
      // Sticking keeps the trial force; sliding scales it down onto the limit, same direction.
      const Vec3 expected = norm(trial) > limit ? trial * (limit / norm(trial)) : trial;
      for (int a = 0; a < 3; ++a) ASSERT_NEAR(f.tangential[a], expected[a], 1e-12 * kParams.kn * 1.0e-5);
      const double scale = kParams.kn * 1.0e-5;
      ASSERT_LE(norm(f.tangential), limit * (1.0 + 1e-12) + 1e-300) << "history " << history << " step " << k;
      ASSERT_NEAR(dot(f.tangential, normal), 0.0, 1e-12 * scale);
      ASSERT_NEAR(dot(s.shear, normal), 0.0, 1e-12 * norm(s.shear) + 1e-300);
      const Vec3 spring = -(kParams.kt * s.shear + (kMass * kParams.gamma_t) * slip);
      for (int a = 0; a < 3; ++a) ASSERT_NEAR(f.tangential[a], spring[a], 1e-12 * scale);
      if (f.normal < 0.0) ++attractive;
      (norm(f.tangential) > limit * (1.0 - 1e-12) ? sliding : sticking)++;
    }
  }
  // The histories must have visited all regimes, or the assertions above proved little.
  EXPECT_GT(sliding, 1000);
  EXPECT_GT(sticking, 1000);
  EXPECT_GT(attractive, 100);
}

// When the normal rotates with no slip, the stored shear is projected into the new tangent plane
// (as LAMMPS does): shear_new = shear_old - (shear_old . n) n, and so is the force.
TEST(LinearDashpot, ShearProjectedIntoRotatedTangentPlane) {
  LinearDashpot::State s;
  const double dt = 1.0e-6, overlap = 1.0e-5;
  for (int k = 0; k < 100; ++k)
    LinearDashpot::force(kParams, s, kinematics({0, 0, 1}, overlap, 0.0, {0.01, 0.005, 0}), dt);
  const Vec3 old_shear = s.shear;
  ASSERT_LT(kParams.kt * norm(old_shear), kParams.friction * kParams.kn * overlap) << "must still stick";
  const double phi = 0.2;
  const Vec3 normal{std::sin(phi), 0.0, std::cos(phi)};
  const auto f = LinearDashpot::force(kParams, s, kinematics(normal, overlap, 0.0, {}), dt);
  const Vec3 expected = old_shear - dot(old_shear, normal) * normal;
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(s.shear[a], expected[a], 1e-14 * norm(old_shear));
    EXPECT_NEAR(f.tangential[a], -kParams.kt * expected[a], 1e-14 * kParams.kt * norm(old_shear));
  }
  EXPECT_NEAR(dot(s.shear, normal), 0.0, 1e-15 * norm(old_shear));
}
