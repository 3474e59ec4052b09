// Hertz–Mindlin: the published benchmark of DEM contact laws (Chung & Ooi, Granular Matter 13,
// 643-656, 2011), run through the engine with the benchmark's materials and speeds, against the
// solutions it compares with: Hertz's elastic impact (peak force, peak overlap, duration) of two
// spheres and of a sphere on a rigid plane; restitution at any impact speed; oblique impacts of a
// sphere on a plane over incident angles 5-85 degrees and impacts with spin, against rigid-body
// sliding where the contact slides throughout, and within the bounds of Coulomb and of energy
// (the tangential spring stores and damps, never creates) where it sticks.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <variant>

#include "grainflow/core/error.hpp"
#include "grainflow/dem/hertz_mindlin.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

struct Material {
  const char* name;
  double youngs_modulus, poisson_ratio, density;
};
// Chung & Ooi's Table 1 materials.
constexpr Material kGlass{"glass", 4.8e10, 0.20, 2800.0};
constexpr Material kLimestone{"limestone", 2.0e10, 0.25, 2500.0};
constexpr Material kAluminiumAlloy{"aluminium_alloy", 7.0e10, 0.30, 2699.0};
constexpr Material kMagnesiumAlloy{"magnesium_alloy", 4.0e10, 0.35, 1800.0};
constexpr Material kAluminiumOxide{"aluminium_oxide", 3.8e11, 0.23, 4000.0};
constexpr Material kCastIron{"cast_iron", 1.0e11, 0.25, 7000.0};

// Hertz's elastic impact at closing speed v: peak overlap (15 m* v^2 / (16 E* sqrt(R*)))^2/5, peak
// force 4/3 E* sqrt(R*) delta^3/2, duration 2 (delta_max / v) int_0^1 dx / sqrt(1 - x^5/2), the
// integral B(2/5, 1/2) / (5/2) = 1.4716.
struct HertzImpact {
  double overlap, force, duration;
};
HertzImpact hertz(double e_star, double r_star, double m_star, double v) {
  const double overlap = std::pow(15.0 * m_star * v * v / (16.0 * e_star * std::sqrt(r_star)), 0.4);
  const double integral = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9) / 2.5;
  return {overlap, 4.0 / 3.0 * e_star * std::sqrt(r_star) * std::pow(overlap, 1.5), 2.0 * integral * overlap / v};
}

double sphere_mass(const Material& m, double radius) { return m.density * 4.0 / 3.0 * M_PI * radius * radius * radius; }

// A case of one or two spheres of `material` (rows of a particle file), no gravity, a rigid wall at
// y = 0 and the rest periodic, stepped at `time_step`.
std::string impact_case(const Material& m, double radius, const std::string& contact, double box, double time_step) {
  std::ostringstream t;
  t.precision(17);
  t << "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [" << box << ", " << box << ", " << box << "]\n"
    << "boundary = { x = \"periodic\", y = \"wall\", z = \"periodic\" }\n"
    << "[gravity]\nvector = [0.0, 0.0, 0.0]\n"
    << "[[species]]\nname = \"" << m.name << "\"\ndiameter = " << 2.0 * radius << "\ndensity = " << m.density
    << "\ncount = 0\nyoungs_modulus = " << m.youngs_modulus << "\npoisson_ratio = " << m.poisson_ratio << "\n"
    << "[contact]\nmodel = \"hertz_mindlin\"\n"
    << contact << "\n"
    << "[run]\nduration = 1.0\ntime_step = " << time_step << "\nskin = " << 0.1 * radius << "\n";
  return t.str();
}

struct Observed {
  double max_overlap = 0.0, max_force = 0.0, duration = 0.0;
  Vec3 velocity, angular_velocity;  // of particle 0 after the contact
};

// Steps until the contact has begun and ended; overlap from the positions, force on particle 0
// (nothing else acts on it), duration from the steps with a force (to within one step).
Observed run_impact(const std::string& case_text, const std::string& rows, bool against_wall, double radius) {
  const test::ParticleFile csv("hm_impact.csv", rows, "species,x,y,z,vx,vy,vz,wx,wy,wz");
  std::string text = case_text;
  text += "[particles]\ninit = \"file\"\nfile = \"" + csv.path() + "\"\n";
  auto engine = test::engine_from_toml(text, "impact.toml", 1);
  Observed o;
  std::visit(
      [&](auto& e) {
        auto& p = e.state().particles;
        bool touched = false;
        long steps_with_force = 0;
        for (long step = 0; step < 2000000; ++step) {
          e.step();
          const double overlap =
              against_wall ? radius - p.position[0][1] : 2.0 * radius - norm(p.position[0] - p.position[1]);
          const double force = norm(p.force[0]);
          if (force > 0.0) {
            touched = true;
            ++steps_with_force;
          }
          o.max_overlap = std::max(o.max_overlap, overlap);
          o.max_force = std::max(o.max_force, force);
          if (touched && overlap < 0.0) break;
        }
        o.duration = steps_with_force * e.state().time_step;
        o.velocity = p.velocity[0];
        o.angular_velocity = p.angular_velocity[0];
      },
      engine);
  return o;
}

std::string row(const Material& m, Vec3 x, Vec3 v, Vec3 w = {}) {
  std::ostringstream t;
  t.precision(17);
  t << m.name << ',' << x[0] << ',' << x[1] << ',' << x[2] << ',' << v[0] << ',' << v[1] << ',' << v[2] << ',' << w[0]
    << ',' << w[1] << ',' << w[2] << '\n';
  return t.str();
}

// Steps per Hertz contact in the benchmark runs: velocity Verlet's error in the peak values and the
// restitution is O((pi / n)^2) ~ 1e-4, and the duration is counted to one step (1/n = 2e-3).
constexpr int kStepsPerContact = 500;

// Test 1: two identical spheres (R = 0.01 m) meet head-on at 10 m/s each (closing speed 20 m/s);
// E* = E / (2 (1 - nu^2)), R* = R / 2, m* = m / 2. For glass the peak overlap is 2.74e-4 m, the
// peak force 10.7 kN and the duration 40.3 us. Bounds: peaks 1e-3 (the discretisation), duration
// 3/n (counted steps).
TEST(ChungOoi, Test1ElasticImpactOfTwoSpheresIsHertzian) {
  for (const Material& m : {kGlass, kLimestone}) {
    const double radius = 0.010, v = 10.0;
    const double e_star = m.youngs_modulus / (2.0 * (1.0 - m.poisson_ratio * m.poisson_ratio));
    const HertzImpact h = hertz(e_star, 0.5 * radius, 0.5 * sphere_mass(m, radius), 2.0 * v);
    const double box = 0.2, y = 0.1;
    const std::string text = impact_case(m, radius, "restitution = 1.0", box, h.duration / kStepsPerContact);
    const std::string rows =
        row(m, {0.1 - radius - 1e-5, y, 0.1}, {v, 0.0, 0.0}) + row(m, {0.1 + radius + 1e-5, y, 0.1}, {-v, 0.0, 0.0});
    const Observed o = run_impact(text, rows, false, radius);
    EXPECT_NEAR(o.max_overlap, h.overlap, 1e-3 * h.overlap) << m.name;
    EXPECT_NEAR(o.max_force, h.force, 1e-3 * h.force) << m.name;
    EXPECT_NEAR(o.duration, h.duration, 3.0 / kStepsPerContact * h.duration) << m.name;
    EXPECT_NEAR(o.velocity[0], -v, 1e-6 * v) << m.name << ": an elastic impact returns the speed";
  }
}

// Test 2: a sphere (R = 0.1 m) hits a rigid plane at 0.2 m/s: E* = E / (1 - nu^2), R* = R, m* = m.
TEST(ChungOoi, Test2ElasticImpactOnARigidPlaneIsHertzian) {
  for (const Material& m : {kAluminiumAlloy, kMagnesiumAlloy}) {
    const double radius = 0.10, v = 0.2;
    const double e_star = m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio);
    const HertzImpact h = hertz(e_star, radius, sphere_mass(m, radius), v);
    const std::string text = impact_case(m, radius, "restitution = 1.0", 1.0, h.duration / kStepsPerContact);
    const Observed o = run_impact(text, row(m, {0.5, radius + 1e-6, 0.5}, {0.0, -v, 0.0}), true, radius);
    EXPECT_NEAR(o.max_overlap, h.overlap, 1e-3 * h.overlap) << m.name;
    EXPECT_NEAR(o.max_force, h.force, 1e-3 * h.force) << m.name;
    EXPECT_NEAR(o.duration, h.duration, 3.0 / kStepsPerContact * h.duration) << m.name;
    EXPECT_NEAR(o.velocity[1], v, 1e-6 * v) << m.name;
  }
}

// Test 3: a sphere (R = 2.5 mm) hits a rigid plane at 3.9 m/s with restitution 0.2 ... 1.0: the
// rebound speed over the impact speed is the coefficient asked for (the benchmark's pass mark),
// and stays so at a tenth and ten times the speed (the damping's form makes e rate-independent).
// Bound 1e-3: velocity Verlet at 500 steps per contact; the law's constant is exact to 1e-12.
TEST(ChungOoi, Test3RestitutionIsTheOneAskedForAtEverySpeed) {
  for (const Material& m : {kAluminiumOxide, kCastIron}) {
    const double radius = 0.0025;
    const double e_star = m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio);
    for (double e : {0.2, 0.4, 0.6, 0.8, 1.0}) {
      for (double v : {0.39, 3.9, 39.0}) {
        const HertzImpact h = hertz(e_star, radius, sphere_mass(m, radius), v);
        const std::string contact = "restitution = " + std::to_string(e);
        const std::string text = impact_case(m, radius, contact, 0.05, h.duration / kStepsPerContact);
        const Observed o = run_impact(text, row(m, {0.025, radius + 1e-7, 0.025}, {0.0, -v, 0.0}), true, radius);
        EXPECT_NEAR(o.velocity[1] / v, e, 1e-3) << m.name << " e = " << e << " v = " << v;
      }
    }
  }
}

// Rigid-body sliding throughout the contact (Coulomb impulse mu J_n, J_n = m (1 + e) v_n): the
// centre's tangential speed drops by mu (1 + e) v_n, the spin changes by (5/2) mu (1 + e) v_n / R,
// and the contact patch's tangential speed by (7/2) mu (1 + e) v_n.
struct Rebound {
  double tangential, spin, patch;
};
Rebound sliding_rebound(double vt, double spin, double vn, double mu, double e, double radius) {
  const double dv = mu * (1.0 + e) * vn;
  const double t = vt - dv, w = spin - 2.5 * dv / radius;
  return {t, w, t + radius * w};
}

// Test 4: aluminium oxide (R = 2.5 mm, mu = 0.092, e = 0.98) hits a rigid plane at 3.9 m/s at
// incident angles 5-85 degrees from the normal. Where v_t > (7/2) mu (1 + e) v_n (above 32.5
// degrees) the contact slides throughout and the tangential restitution v_t'/v_t, the rebound spin
// and the contact patch's rebound angle are rigid-body sliding's (Kharaz, Gorham & Salman 2001
// measured the same above about 30 degrees); bound 1e-3 of the tangential speed (the normal
// impulse's discretisation, and a few steps of sticking at first touch). Below, the contact
// sticks: the spin stays within Coulomb's bound, and the patch leaves slower than it came, the
// tangential spring storing and damping energy but never creating it. (A history spring that is
// not scaled down as the patch shrinks creates it: at no slip, e = 1 and nu = 0.23 it returns
// 1.0135 of the patch's speed, an integration of the two-degree-of-freedom contact shows.)
TEST(ChungOoi, Test4ObliqueImpactsFollowSlidingAboveTheCriticalAngleAndReverseBelow) {
  const Material m = kAluminiumOxide;
  const double radius = 0.0025, speed = 3.9, mu = 0.092, e = 0.98;
  const double e_star = m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio);
  const double critical = std::atan(3.5 * mu * (1.0 + e)) * 180.0 / M_PI;
  for (double angle : {5.0, 10.0, 20.0, 30.0, 35.0, 45.0, 60.0, 75.0, 85.0}) {
    const double a = angle * M_PI / 180.0, vn = speed * std::cos(a), vt = speed * std::sin(a);
    const HertzImpact h = hertz(e_star, radius, sphere_mass(m, radius), vn);
    const std::string contact = "restitution = 0.98\nfriction = 0.092";
    const std::string text = impact_case(m, radius, contact, 0.05, h.duration / kStepsPerContact);
    const Observed o = run_impact(text, row(m, {0.025, radius + 1e-7, 0.025}, {vt, -vn, 0.0}), true, radius);
    const double spin = o.angular_velocity[2], patch = o.velocity[0] + radius * spin;
    const Rebound sliding = sliding_rebound(vt, 0.0, vn, mu, e, radius);
    EXPECT_NEAR(o.velocity[1], e * vn, 1e-3 * vn) << angle << " degrees";
    // Where the patch leaves slower than it came the sphere lost tangential and spin energy: with
    // impulse J, Delta E = J (7 J / 4m - v_t) < 0 exactly when |v_t - 7 J / 2m| < v_t.
    if (angle > critical + 1.0) {
      EXPECT_NEAR(o.velocity[0] / vt, sliding.tangential / vt, 1e-3) << angle << " degrees";
      EXPECT_NEAR(spin, sliding.spin, 1e-3 * std::fabs(sliding.spin)) << angle << " degrees";
      const double rebound_angle = std::atan2(patch, o.velocity[1]), expected = std::atan2(sliding.patch, e * vn);
      EXPECT_NEAR(rebound_angle, expected, 1e-3) << angle << " degrees";
    } else {
      EXPECT_GE(spin, sliding.spin * (1.0 + 1e-3)) << angle << " degrees: more spin than sliding allows";
      EXPECT_LT(spin, 0.0) << angle << " degrees";
      EXPECT_LT(std::fabs(patch), vt) << angle << " degrees: the tangential spring gave back more than it took";
    }
  }
}

// Tests 5-6 with spin: a sphere with no tangential speed but backspin meets the plane (aluminium
// alloy, R = 0.1 m, v_n = 0.2 m/s, mu = 0.4, e = 0.5); at R w0 > (7/2) mu (1 + e) v_n it slides
// throughout and leaves with the sliding impulse's speed and spin, in either sense of the spin.
TEST(ChungOoi, ImpactsWithSpinFollowSliding) {
  const Material m = kAluminiumAlloy;
  const double radius = 0.1, vn = 0.2, mu = 0.4, e = 0.5;
  const double e_star = m.youngs_modulus / (1.0 - m.poisson_ratio * m.poisson_ratio);
  const HertzImpact h = hertz(e_star, radius, sphere_mass(m, radius), vn);
  for (double w0 : {-8.0, -5.0, 5.0, 8.0}) {  // rad/s: R w0 = 0.5-0.8 m/s against (7/2) mu (1 + e) v_n = 0.42
    const std::string text =
        impact_case(m, radius, "restitution = 0.5\nfriction = 0.4", 1.0, h.duration / kStepsPerContact);
    const Observed o =
        run_impact(text, row(m, {0.5, radius + 1e-6, 0.5}, {0.0, -vn, 0.0}, {0.0, 0.0, w0}), true, radius);
    // The patch slides along +x for w0 > 0 (slip = v_x + R w_z): friction pushes the centre along -x.
    const double sign = w0 > 0.0 ? 1.0 : -1.0;
    const double dv = mu * (1.0 + e) * vn;
    EXPECT_NEAR(o.velocity[0], -sign * dv, 1e-3 * dv) << "w0 = " << w0;
    EXPECT_NEAR(o.angular_velocity[2], w0 - sign * 2.5 * dv / radius, 1e-3 * 2.5 * dv / radius) << "w0 = " << w0;
    EXPECT_NEAR(o.velocity[1], e * vn, 1e-3 * vn) << "w0 = " << w0;
  }
}

// The damping constant for e: the scaled impact rebounds with e to 1e-9, the elastic one lasts
// Hertz's 2 B(2/5, 1/2) / (5/2) (5/4)^2/5 scaled units, and the constant is larger than the
// linear-oscillator estimate -2 sqrt(5/6) ln e / sqrt(ln^2 e + pi^2) of LIGGGHTS and EDEM, which
// holds only where the damped force may pull: without pulling it gives e = 0.55 for 0.5 (the
// estimate's error Thornton et al. 2013 tabulate).
TEST(HertzMindlin, DampingConstantGivesTheRestitutionExactly) {
  const double integral = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9) / 2.5;
  EXPECT_NEAR(HertzMindlin::scaled_impact(0.0).duration, 2.0 * integral * std::pow(1.25, 0.4), 1e-6);
  EXPECT_NEAR(HertzMindlin::scaled_impact(0.0).restitution, 1.0, 1e-9);
  for (double e : {0.05, 0.2, 0.5, 0.8, 0.95, 0.999}) {
    const double c = HertzMindlin::damping_for(e);
    EXPECT_NEAR(HertzMindlin::scaled_impact(c).restitution, e, 1e-9) << e;
    const double beta = std::log(e) / std::sqrt(std::log(e) * std::log(e) + M_PI * M_PI);
    const double estimate = -2.0 * std::sqrt(5.0 / 6.0) * beta;
    EXPECT_GT(c, estimate) << e;
    EXPECT_GT(HertzMindlin::scaled_impact(estimate).restitution, e) << e;
  }
  EXPECT_NEAR(HertzMindlin::scaled_impact(-2.0 * std::sqrt(5.0 / 6.0) * std::log(0.5) /
                                          std::sqrt(std::log(0.5) * std::log(0.5) + M_PI * M_PI))
                  .restitution,
              0.550, 0.001);
}

// A wall of its own material: E* combines both bodies' compliances, so a wall as stiff as the
// sphere gives the peak overlap of two spheres' E* (1/E* = 2 (1 - nu^2) / E) at R* = R.
TEST(HertzMindlin, WallOfItsOwnMaterialCombinesCompliances) {
  const HertzMindlin::Params rigid =
      HertzMindlin::make(7.0e10, 0.3, 1.0, 0.0, std::numeric_limits<double>::infinity(), 0.0);
  const HertzMindlin::Params same = HertzMindlin::make(7.0e10, 0.3, 1.0, 0.0, 7.0e10, 0.3);
  EXPECT_DOUBLE_EQ(rigid.e_star, 7.0e10 / 0.91);
  EXPECT_DOUBLE_EQ(same.e_star, 7.0e10 / 1.82);
  EXPECT_DOUBLE_EQ(rigid.g_star, 7.0e10 / (2.0 * 1.7 * 1.3));
  EXPECT_DOUBLE_EQ(same.g_star, 7.0e10 / (4.0 * 1.7 * 1.3));
}

// Bad input is refused by key: a species without a Young's modulus, a Poisson ratio outside
// [0, 0.5), species of two materials, a wall's Poisson ratio out of range.
TEST(HertzMindlin, BadMaterialsAreRefusedByKey) {
  auto case_with = [](const std::string& species, const std::string& wall) {
    return "[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.02, 0.02, 0.02]\n"
           "boundary = { x = \"periodic\", y = \"wall\", z = \"periodic\" }\n"
           "[[species]]\nname = \"a\"\ndiameter = 0.002\ndensity = 2500.0\ncount = 10\n" +
           species + "\n[contact]\nmodel = \"hertz_mindlin\"\nrestitution = 0.8\n[walls.ylo]\n" + wall +
           "\n[run]\nduration = 0.01\n";
  };
  auto refused_key = [&](const std::string& species, const std::string& wall) -> std::string {
    try {
      load_case_from_string(case_with(species, wall), "bad.toml");
    } catch (const InputError& e) {
      return e.key();
    }
    return "accepted";
  };
  EXPECT_EQ(refused_key("", ""), "species.youngs_modulus");
  EXPECT_EQ(refused_key("youngs_modulus = 1e8\npoisson_ratio = 0.5", ""), "species.0.poisson_ratio");
  EXPECT_EQ(refused_key("youngs_modulus = 1e8\npoisson_ratio = -0.1", ""), "species.0.poisson_ratio");
  EXPECT_EQ(refused_key("youngs_modulus = 1e8\n[[species]]\nname = \"b\"\ndiameter = 0.002\ndensity = 2500.0\n"
                        "count = 10\nyoungs_modulus = 2e8",
                        ""),
            "species.youngs_modulus");
  EXPECT_EQ(refused_key("youngs_modulus = 1e8", "poisson_ratio = 0.7"), "walls.ylo.poisson_ratio");
  EXPECT_EQ(refused_key("youngs_modulus = 1e8", "youngs_modulus = -1.0"), "walls.ylo.youngs_modulus");
  EXPECT_EQ(refused_key("youngs_modulus = 1e8", ""), "accepted");
}

}  // namespace
