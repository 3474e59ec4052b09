// JKR adhesion against the closed forms of Johnson, Kendall & Roberts (1971) as Thornton states
// them (F_c = 3 pi Gamma R*): the force-overlap curve's landmarks, its potential, and through the
// engine Thornton's pull-off force (a sphere hanging from a ceiling holds a weight just below F_c
// and falls under one just above) and the hysteresis of contact breaking (an elastic sphere sticks
// below the speed whose kinetic energy the two jumps of the curve take, and above it rebounds with
// e = sqrt(1 - (v_s / v)^2)).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <cstdio>
#include <sstream>
#include <string>
#include <variant>

#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/jkr.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

constexpr double kE = 1.0e8, kNu = 0.25, kGamma = 0.05;  // Pa, -, J/m^2
constexpr double kRadius = 1.0e-3;                       // m, the sphere
constexpr double kDensity = 2500.0;

Jkr::Params params(double restitution, double surface_energy) {
  return {HertzMindlin::make(kE, kNu, restitution, 0.0, std::numeric_limits<double>::infinity(), 0.0), surface_energy};
}

double force_at(const Jkr::Params& p, double overlap, double r) {
  Jkr::State s;
  ContactKinematics k;
  k.normal = {0.0, 1.0, 0.0};
  k.overlap = overlap;
  k.effective_mass = 1e-5;
  k.effective_radius = r;
  return Jkr::force(p, s, k, 0.0).normal;  // at rest: no damping
}

// The landmarks of the curve (a sphere of R* = 1 mm on a rigid plane), to 1e-9 (the Newton root
// is found to 1e-15 of sqrt(a)): snap-on at delta = 0 with F = -8/9 F_c, zero force at
// delta_0 = a0^2 / (3 R*), the pull-off force -F_c at the curve's minimum, and the neck breaking at
// delta_c = -(3/4) (pi^2 w^2 R / E*^2)^1/3 with F = -5/9 F_c.
TEST(Jkr, ForceCurveHasJohnsonKendallRobertsLandmarks) {
  const Jkr::Params p = params(1.0, kGamma);
  const double e = p.material.e_star, w = 2.0 * kGamma, r = kRadius;
  const double fc = 3.0 * M_PI * kGamma * r;
  EXPECT_DOUBLE_EQ(Jkr::pull_off_force(p, r), fc);
  EXPECT_NEAR(force_at(p, 0.0, r), -8.0 / 9.0 * fc, 1e-9 * fc);
  const double a0 = std::cbrt(9.0 * M_PI * w * r * r / (2.0 * e));
  EXPECT_NEAR(force_at(p, a0 * a0 / (3.0 * r), r), 0.0, 1e-9 * fc);
  const double detach = -0.75 * std::cbrt(M_PI * M_PI * w * w * r / (e * e));
  EXPECT_NEAR(Jkr::detach_overlap(p, r), detach, 1e-15 * std::fabs(detach));
  EXPECT_NEAR(force_at(p, detach, r), -5.0 / 9.0 * fc, 1e-7 * fc);
  // The minimum over a fine scan of the stable branch, from the neck to zero load.
  double lowest = 0.0;
  const int n = 200000;
  for (int i = 0; i <= n; ++i)
    lowest = std::min(lowest, force_at(p, detach + (a0 * a0 / (3.0 * r) - detach) * i / n, r));
  EXPECT_NEAR(lowest, -fc, 1e-8 * fc);
  // Without surface energy it is Hertz: 4/3 E* sqrt(R*) delta^3/2.
  const Jkr::Params hertz = params(1.0, 0.0);
  EXPECT_NEAR(force_at(hertz, 1e-6, r), 4.0 / 3.0 * e * std::sqrt(r) * 1e-9, 1e-12 * e * std::sqrt(r) * 1e-9);
  EXPECT_EQ(force_at(hertz, -1e-9, r), 0.0);
}

// The energy the engine books is the curve's potential: dU/d delta = F along the branch (central
// differences, error ~ h^2 F''' ~ 1e-8 of F_c), so the energy budget closes with adhesion.
TEST(Jkr, ElasticEnergyIsThePotentialOfTheForce) {
  const Jkr::Params p = params(1.0, kGamma);
  const double r = kRadius, fc = Jkr::pull_off_force(p, r);
  const double detach = Jkr::detach_overlap(p, r);
  const Jkr::State memory;
  for (double overlap : {0.9 * detach, 0.3 * detach, 1e-9, -0.5 * detach, -3.0 * detach, -20.0 * detach}) {
    const double h = 1e-4 * std::fabs(detach);
    const double slope =
        (Jkr::elastic_energy(p, memory, overlap + h, r) - Jkr::elastic_energy(p, memory, overlap - h, r)) / (2 * h);
    EXPECT_NEAR(slope, force_at(p, overlap, r), 1e-6 * fc) << "overlap " << overlap;
  }
}

// The case of one sphere under a ceiling (yhi wall) or above a floor, JKR with the wall.
std::string sphere_case(const std::string& file, double gravity, double restitution, const std::string& face,
                        int collision_steps) {
  std::ostringstream t;
  t.precision(17);
  t << "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.02, 0.02, 0.02]\n"
    << "boundary = { x = \"periodic\", y = " << (face == "yhi" ? "[\"open\", \"wall\"]" : "[\"wall\", \"open\"]")
    << ", z = \"periodic\" }\n"
    << "[gravity]\nvector = [0.0, " << gravity << ", 0.0]\n"
    << "[[species]]\nname = \"glass\"\ndiameter = " << 2.0 * kRadius << "\ndensity = " << kDensity
    << "\nyoungs_modulus = " << kE << "\npoisson_ratio = " << kNu << "\n"
    << "[particles]\ninit = \"file\"\nfile = \"" << file << "\"\n"
    << "[contact]\nmodel = \"jkr\"\nrestitution = " << restitution << "\nsurface_energy = " << kGamma << "\n"
    << "[run]\nduration = 1.0\ncollision_steps = " << collision_steps << "\n";
  return t.str();
}

// Thornton's pull-off force through the engine, under force control: a sphere stuck to a ceiling
// (set in contact at zero load and damped nearly critically, e = 0.01, so that the weight's
// sudden pull overshoots by ~1 %) under a weight of 0.95 F_c finds its equilibrium on the neck and
// stays; under 1.05 F_c there is none and it falls. The wall contact's R* is the sphere's radius.
TEST(Jkr, SphereHangsFromACeilingBelowThePullOffForceAndFallsAbove) {
  const double mass = kDensity * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  const Jkr::Params p = params(0.01, kGamma);
  const double e = p.material.e_star, w = 2.0 * kGamma, r = kRadius;
  const double a0 = std::cbrt(9.0 * M_PI * w * r * r / (2.0 * e));
  const double start = a0 * a0 / (3.0 * r);  // zero-load overlap
  const double fc = Jkr::pull_off_force(p, r);
  for (double load : {0.95, 1.05}) {
    std::ostringstream row;
    row.precision(17);
    row << "glass,0.01," << 0.02 - (kRadius - start) << ",0.01,0,0,0\n";
    const test::ParticleFile csv("hanging.csv", row.str());
    const double g = load * fc / mass;
    auto engine =
        test::engine_from_toml(sphere_case(csv.path(), -g, 0.01, "yhi", 20), testing::TempDir() + "hang.toml", 1);
    std::visit(
        [&](auto& eng) {
          const auto& s = eng.state().particles;
          const double y0 = s.position[0].y;
          // Held: settled well within 0.05 s (~4 damping times). Pulled off: the creep to the neck
          // takes ~8 ms; then 10 ms of free fall (1 mm).
          double detached = -1.0;
          while (eng.state().time < 0.05) {
            eng.step();
            if (detached < 0.0 && eng.statistics().wall_contacts == 0) detached = eng.state().time;
            if (detached > 0.0 && eng.state().time > detached + 0.01) break;
          }
          const double drop = y0 - s.position[0].y;
          if (load < 1.0) {
            EXPECT_EQ(eng.statistics().wall_contacts, 1) << "fell off at " << load << " F_c";
            EXPECT_LT(drop, 10.0 * std::fabs(Jkr::detach_overlap(p, r)) + start);
            EXPECT_LT(std::fabs(s.velocity[0].y), 1e-6);
          } else {
            EXPECT_EQ(eng.statistics().wall_contacts, 0) << "held " << load << " F_c";
            EXPECT_GT(drop, 1e-4) << "still at the ceiling under " << load << " F_c";
          }
        },
        engine);
  }
}

// Hysteresis: an elastic sphere (restitution 1, no damping) meets a plane at speed v. The jumps
// of the curve at snap-on and at the neck's break take W = U(a_c) - U(a(0)) of its kinetic energy,
// so it sticks below v_s = sqrt(2 W / m) and rebounds with e = sqrt(1 - (v_s / v)^2) above. With
// dt = 1e-7 s the contact (~2e-4 s) takes ~2000 steps: the jumps are placed to within a step and
// Verlet's energy error is far smaller, ~1e-3 of W in all; 5e-3 on e is a few times that and far
// below the difference a wrong jump makes (dropping the snap-on's 0.48 of W moves e by 0.1).
TEST(Jkr, ElasticImpactSticksBelowTheHysteresisSpeedAndReboundsAbove) {
  const double mass = kDensity * 4.0 / 3.0 * M_PI * std::pow(kRadius, 3);
  const Jkr::Params p = params(1.0, kGamma);
  const HeadOnImpact on_wall{mass, kRadius, 0.0};
  const double vs = Jkr::sticking_speed(p, on_wall);
  ASSERT_GT(vs, 1e-3);
  ASSERT_LT(vs, 1e-2);
  for (double ratio : {0.8, 1.5, 3.0}) {
    const double v = ratio * vs;
    std::ostringstream row;
    row.precision(17);
    row << "glass,0.01," << kRadius + 1e-9 << ",0.01,0," << -v << ",0\n";
    const test::ParticleFile csv("impact.csv", row.str());
    const std::string text = sphere_case(csv.path(), 0.0, 1.0, "ylo", 20) + "time_step = 1.0e-7\n";
    auto engine = test::engine_from_toml(text, testing::TempDir() + "impact.toml", 1);
    std::visit(
        [&](auto& eng) {
          while (eng.state().time < 3e-3) eng.step();
          const double vy = eng.state().particles.velocity[0].y;
          if (ratio < 1.0) {
            EXPECT_EQ(eng.statistics().wall_contacts, 1) << "bounced off at " << ratio << " v_s";
          } else {
            EXPECT_EQ(eng.statistics().wall_contacts, 0) << "stuck at " << ratio << " v_s";
            EXPECT_NEAR(vy / v, std::sqrt(1.0 - 1.0 / (ratio * ratio)), 5e-3) << ratio << " v_s";
          }
        },
        engine);
    // The law's own head-on impact (check's line, the time step's duration) agrees.
    HeadOnImpact impact = on_wall;
    impact.speed = v;
    const BinaryContact b = Jkr::binary_contact(p, impact);
    if (ratio < 1.0) {
      EXPECT_TRUE(std::isinf(b.duration)) << ratio;
    } else {
      EXPECT_NEAR(b.restitution, std::sqrt(1.0 - 1.0 / (ratio * ratio)), 1e-3) << ratio;
    }
  }
}

}  // namespace

namespace {

// A bonded pair's small normal oscillations about a0: the curve's slope there (closed form) against
// a central difference of the force, and the period of m* delta'' = -F(delta) integrated with a
// step 1e-4 of it (velocity Verlet: period error ~1e-8) against 2 pi sqrt(m* / k0), to 1e-4.
TEST(Jkr, BondedPairOscillatesAtTheCurvesSlopeAndBoundsTheTimeStep) {
  const Jkr::Params p = params(1.0, kGamma);
  const double r = kRadius;
  const double a0 = Jkr::equilibrium_radius(p, r);
  const double delta0 = a0 * a0 / (3.0 * r);
  const double k0 = Jkr::normal_stiffness(p, a0, r);
  const double h = 1e-6 * delta0;
  EXPECT_NEAR((force_at(p, delta0 - h, r) - force_at(p, delta0 + h, r)) / (2.0 * h), -k0, 1e-5 * k0);
  // At zero load dF/da = 2 E* a0^2 / R* and d delta / da = 5 a0 / (3 R*): k0 = 6/5 E* a0.
  EXPECT_NEAR(k0, 1.2 * p.material.e_star * a0, 1e-12 * k0);

  const double mass = 4.0 / 3.0 * M_PI * r * r * r * kDensity;  // a sphere bonded to a plane
  const double period = 2.0 * M_PI * std::sqrt(mass / k0);
  const double dt = 1e-4 * period;
  double x = delta0 + 1e-3 * delta0, v = 0.0, a = -force_at(p, x, r) / mass;
  double previous_v = v, t = 0.0, crossing = -1.0;
  int crossings = 0;
  while (crossings < 3 && t < 10.0 * period) {  // v changes sign at each turning point
    v += 0.5 * dt * a;
    x += dt * v;
    a = -force_at(p, x, r) / mass;
    v += 0.5 * dt * a;
    t += dt;
    if (previous_v * v < 0.0) {
      ++crossings;
      if (crossings == 1) crossing = t;
      if (crossings == 3) {
        EXPECT_NEAR(t - crossing, period, 1e-4 * period);
      }
    }
    previous_v = v;
  }
  EXPECT_EQ(crossings, 3);

  // The time step resolves the bonded pair's half period in collision_steps.
  const HeadOnImpact pair{mass, r, 0.01};
  EXPECT_DOUBLE_EQ(Jkr::bonded_half_period(p, pair), 0.5 * period);  // no friction: the normal mode
  EXPECT_LE(Jkr::time_step(p, pair, 40), 0.5 * period / 40.0);
  const Jkr::Params frictional{HertzMindlin::make(kE, kNu, 1.0, 0.5, std::numeric_limits<double>::infinity(), 0.0),
                               kGamma};
  const double tangential = M_PI * std::sqrt(2.0 / 7.0 * mass / (8.0 * frictional.material.g_star * a0));
  EXPECT_DOUBLE_EQ(Jkr::bonded_half_period(frictional, pair), std::min(0.5 * period, tangential));
  // Without adhesion the bound is Hertz–Mindlin's.
  const Jkr::Params dry = params(1.0, 0.0);
  EXPECT_DOUBLE_EQ(Jkr::time_step(dry, pair, 40), HertzMindlin::time_step(dry.material, pair, 40));
}

}  // namespace
