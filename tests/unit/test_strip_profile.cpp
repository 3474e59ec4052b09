// Campbell's strip profiles (src/grainflow/observe/strip_profile.hpp) against exact geometry and
// equilibrium statistics: the solids fraction of static lattices (exact disc-strip areas and
// sphere-slab volumes), the mass-weighted mean velocity of a disc straddling two strips, the
// temperature about the time mean against Lan's about the instantaneous mean, the rotational
// temperature with beta = R^2 / 2, and equipartition in an elastic gas of rough discs run by the
// event-driven engine.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/edmd/edmd_engine.hpp"
#include "grainflow/observe/strip_profile.hpp"

#include "elastic_gas_case.hpp"

using namespace grainflow;
using namespace grainflow::observe;
namespace q = grainflow::observe::strip;

namespace {

// A free particle of radius r and mass m with moment of inertia beta m r^2.
void add(ParticleStore& p, Vec3 x, double r, double m, Vec3 v, Vec3 omega = {}, double beta = 0.5) {
  const std::size_t i = p.size();
  p.resize(i + 1);
  p.position[i] = x;
  p.radius[i] = p.target_radius[i] = r;
  p.mass[i] = m;
  p.inv_mass[i] = 1.0 / m;
  p.inv_inertia[i] = 1.0 / (beta * m * r * r);
  p.velocity[i] = v;
  p.angular_velocity[i] = omega;
  p.id[i] = static_cast<std::uint32_t>(i);
  p.motion[i] = Motion::free;
}

// Area of the part of a disc of radius r beyond a chord at distance r - h from its centre.
double segment_area(double r, double h) {
  return r * r * std::acos((r - h) / r) - (r - h) * std::sqrt(2.0 * r * h - h * h);
}

}  // namespace

// A square lattice of discs, spacing a, rows at an arbitrary offset from the strip boundaries:
// strips one spacing thick each hold exactly one disc per column, whatever the offset (the pieces
// cut off at one boundary come back at the other), so nu = pi R^2 / a^2 in every strip away from
// the lattice's ends. With a = 2R (touching discs) that is Campbell's pi/4.
TEST(StripProfile, SquareLatticeHasItsPackingFractionInEveryStrip) {
  for (const double a : {2.0, 2.5, 3.7}) {
    for (const double offset : {0.5, 0.3, 0.0}) {  // rows at (k + offset) a: centred, off-centre, on boundaries
      const double r = 1.0;
      const int columns = 6, rows = 10;
      ParticleStore p;
      for (int i = 0; i < columns; ++i)
        for (int k = 0; k < rows; ++k) add(p, {(i + 0.5) * a, (k + offset) * a, 0.0}, r, 1.0, {});
      StripProfile profile(2, 10);
      profile.sample(p, StripGrid(2, 1, 0.0, 10 * a, 10, columns * a));
      const auto strips = profile.averages();
      // The end strips miss the pieces beyond the lattice when the rows are not centred in them.
      for (int k = 1; k < 9; ++k)
        EXPECT_NEAR(strips[k].value[q::solids_fraction], M_PI * r * r / (a * a), 1e-12)
            << "a " << a << " offset " << offset << " strip " << k;
      if (a == 2.0 && offset == 0.5) {
        EXPECT_NEAR(strips[0].value[q::solids_fraction], kDiscSquarePacking, 1e-12);
      }
    }
  }
}

// Spheres on a simple cubic lattice of spacing a in slabs one spacing thick: pi d^3 / (6 a^3);
// touching spheres give pi/6, the spheres' counterpart of pi/4.
TEST(StripProfile, SimpleCubicLatticeHasItsPackingFractionInEverySlab) {
  const double r = 0.5, a = 1.0;
  ParticleStore p;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 8; ++j)
      for (int k = 0; k < 3; ++k) add(p, {(i + 0.5) * a, (j + 0.27) * a, (k + 0.5) * a}, r, 1.0, {});
  StripProfile profile(3, 8);
  profile.sample(p, StripGrid(3, 1, 0.0, 8 * a, 8, 4 * a * 3 * a));
  const auto strips = profile.averages();
  // The end slabs miss the caps beyond the lattice.
  for (int k = 1; k < 7; ++k) EXPECT_NEAR(strips[k].value[q::solids_fraction], kSphereCubicPacking, 1e-12) << k;
}

// Disc 1 (unit mass) lies wholly in strip 0 = [0, 2]; disc 2 (mass 3) is centred at 2.5 and so has
// a segment of height 0.5 below y = 2 in strip 0, the rest in strip 1. Strip 0's mean velocity is
// the mass-weighted mean with disc 2 counting by its area share f; strip 1 holds disc 2 alone.
TEST(StripProfile, MassWeightedMeanVelocityCountsTheStraddlingDiscByItsShare) {
  ParticleStore p;
  add(p, {1.0, 1.0, 0.0}, 1.0, 1.0, {2.0, 0.5, 0.0});
  add(p, {3.0, 2.5, 0.0}, 1.0, 3.0, {-1.0, 1.5, 0.0});
  StripProfile profile(2, 2);
  const StripGrid grid(2, 1, 0.0, 4.0, 2, 6.0);
  profile.sample(p, grid);
  const auto strips = profile.averages();
  const double f = segment_area(1.0, 0.5) / M_PI;
  EXPECT_NEAR(strips[0].value[q::u], (1.0 * 2.0 + 3.0 * f * -1.0) / (1.0 + 3.0 * f), 1e-12);
  EXPECT_NEAR(strips[0].value[q::v], (1.0 * 0.5 + 3.0 * f * 1.5) / (1.0 + 3.0 * f), 1e-12);
  EXPECT_NEAR(strips[1].value[q::u], -1.0, 1e-12);
  EXPECT_NEAR(strips[0].value[q::particles], 1.0 + f, 1e-12);
  EXPECT_NEAR(strips[0].value[q::solids_fraction], M_PI * (1.0 + f) / grid.measure(), 1e-12);
  EXPECT_NEAR(strips[1].value[q::solids_fraction], M_PI * (1.0 - f) / grid.measure(), 1e-12);
}

// Two equal discs in one strip move at U(t) +- delta along x and +-delta_v along y, with
// U(t) = U0 + A cos(2 pi s / P) over whole periods of samples s. About the instantaneous strip mean
// (Lan) the fluctuations are delta^2 and delta_v^2; about the time mean (Campbell) <u'^2> adds the
// variance of U, A^2 / 2, so the per-degree-of-freedom temperatures differ by A^2 / (2 D).
TEST(StripProfile, TemperatureAboutTheTimeMeanAddsTheVarianceOfTheStripVelocity) {
  const double u0 = 0.7, amplitude = 0.4, delta = 0.1, delta_v = 0.05;
  const int period = 16, periods = 40;
  StripProfile profile(2, 1);
  const StripGrid grid(2, 1, 0.0, 4.0, 1, 10.0);
  for (int s = 0; s < period * periods; ++s) {
    const double u = u0 + amplitude * std::cos(2.0 * M_PI * s / period);
    ParticleStore p;
    add(p, {2.0, 1.5, 0.0}, 1.0, 1.0, {u + delta, delta_v, 0.0});
    add(p, {6.0, 2.5, 0.0}, 1.0, 1.0, {u - delta, -delta_v, 0.0});
    profile.sample(p, grid);
  }
  const auto a = profile.averages()[0];
  const auto& x = a.value;
  EXPECT_NEAR(x[q::u], u0, 1e-12);
  EXPECT_NEAR(x[q::v], 0.0, 1e-12);
  EXPECT_NEAR(x[q::u_variance], delta * delta + 0.5 * amplitude * amplitude, 1e-12);
  EXPECT_NEAR(x[q::v_variance], delta_v * delta_v, 1e-12);
  // <uv> - <u><v>: the discs' x and y deviations go together, so the cross moment is delta delta_v.
  EXPECT_NEAR(x[q::uv_covariance], delta * delta_v, 1e-12);
  EXPECT_NEAR(x[q::temperature_lan], 0.5 * (delta * delta + delta_v * delta_v), 1e-12);
  EXPECT_NEAR(x[q::granular_temperature] - x[q::temperature_lan], 0.25 * amplitude * amplitude, 1e-12);
  // Unit masses, no spin: Campbell's temperature is 1/2 m (<u'^2> + <v'^2>), all translational.
  EXPECT_NEAR(x[q::temperature], 0.5 * (x[q::u_variance] + x[q::v_variance]), 1e-12);
  EXPECT_NEAR(x[q::translational_temperature], x[q::temperature], 1e-12);
  // Lan's temperature is the same in every sample: its error bar is zero. The mean velocity repeats
  // every 16 samples, so blocks of 16 or more have identical means (error ~ round-off).
  EXPECT_NEAR(a.error[q::temperature_lan], 0.0, 1e-12);
  EXPECT_TRUE(std::isfinite(a.error[q::u]));
}

// Discs of radius R with I = m R^2 / 2 (beta = R^2 / 2) spinning at <omega> +- omega_0:
// beta <omega'^2> = R^2 omega_0^2 / 2 whatever the mean spin; Campbell's temperature adds it to the
// translational fluctuations, 1/2 m (<u'^2> + <v'^2> + beta <omega'^2>).
TEST(StripProfile, RotationalTemperatureUsesBetaOfDiscs) {
  const double r = 1.5, m = 2.0, mean_spin = 3.0, omega0 = 0.8, a = 0.3, b = 0.2;
  ParticleStore p;
  add(p, {2.0, 2.0, 0.0}, r, m, {a, b, 0.0}, {0.0, 0.0, mean_spin + omega0});
  add(p, {6.0, 2.0, 0.0}, r, m, {-a, -b, 0.0}, {0.0, 0.0, mean_spin - omega0});
  StripProfile profile(2, 1);
  profile.sample(p, StripGrid(2, 1, 0.0, 4.0, 1, 10.0));
  const auto averages = profile.averages();  // by value: keep it alive while x refers into it
  const auto& x = averages[0].value;
  const double rotational = 0.5 * r * r * omega0 * omega0;
  EXPECT_NEAR(x[q::omega_z], mean_spin, 1e-12);
  EXPECT_NEAR(x[q::rotational_temperature], rotational, 1e-12);
  EXPECT_NEAR(x[q::temperature], 0.5 * m * (a * a + b * b + rotational), 1e-12);
  EXPECT_NEAR(x[q::translational_temperature], 0.5 * m * (a * a + b * b), 1e-12);
}

// An elastic gas of perfectly rough discs (tangential restitution +1, beta = R^2/2) between two
// smooth elastic walls, periodic along x, no gravity: energy is conserved and shared equally by the
// 3N - 1 quadratic degrees of freedom left once the conserved x momentum is taken out,
// T = 2 (E - P_x^2 / 2M) / (3N - 1) per degree of freedom (unit masses). Every strip then shows
// <v'^2> = beta <omega'^2> = T and <u'^2> = T (N - 1) / N: the N x velocities about their fixed mean
// have only N - 1 degrees of freedom (with N = 100 a 1 % effect, about one error bar here, which the
// test sees: without it the strips' <u'^2> fall 1.2 standard errors low on average over 8 seeds).
TEST(StripProfile, ElasticRoughDiscsShareEnergyEquallyInEveryStrip) {
#ifdef NDEBUG
  constexpr double kDuration = 4000.0;  // ~2 collisions per disc per unit time: 0.3 s
#else
  constexpr double kDuration = 800.0;  // sanitizer builds run ~20 times slower
#endif
  // 100 unit discs of diameter 1 between smooth walls 20 apart: lattice spacing 2, area fraction pi/16.
  const std::string text = test::elastic_gas_case({2, 10, M_PI / 16.0, 1.0, 1.0, true, 11});
  edmd::EdmdEngine<2> engine(edmd::build_edmd_state(load_case_from_string(text, "rough_gas.toml")));
  const ParticleStore& p = engine.state().particles;
  double energy = 0.0, mass = 0.0, px = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    energy += 0.5 * p.mass[i] * norm2(p.velocity[i]) + 0.5 * norm2(p.angular_velocity[i]) / p.inv_inertia[i];
    mass += p.mass[i];
    px += p.mass[i] * p.velocity[i].x;
  }
  const double n = static_cast<double>(p.size()), m = mass / n;  // unit mass: density 4/pi per area
  const double temperature = 2.0 * (energy - px * px / (2.0 * mass)) / ((3.0 * n - 1.0) * m);
  const double u_temperature = temperature * (n - 1.0) / n;

  engine.advance_to(50.0);  // some 50 collisions per disc: translation and rotation equilibrated
  StripProfile profile(2, 5);
  const StripGrid grid(2, 1, 0.0, 20.0, 5, 20.0);
  // Samples 2 time units (~4 collisions per disc) apart: with closer ones the blocks of the error
  // bars fall short of the slow density and temperature modes of the box and the errors run ~25 % low.
  for (double t = 52.0; t <= 50.0 + kDuration; t += 2.0) {
    engine.advance_to(t);
    profile.sample(engine.state().particles, grid);
  }
  for (const auto& a : profile.averages()) {
    // 4 standard errors (block-averaged; over 8 seeds the deviations had an rms of 0.97 of them, the
    // largest 2.1): a false alarm in one of these 15 comparisons has a chance below 0.1 %.
    for (const int quantity : {q::u_variance, q::v_variance, q::rotational_temperature}) {
      ASSERT_TRUE(std::isfinite(a.error[quantity]));
      const double expected = quantity == q::u_variance ? u_temperature : temperature;
      EXPECT_NEAR(a.value[quantity], expected, 4.0 * a.error[quantity])
          << "strip at y = " << a.centre << ", quantity " << quantity << ", error " << a.error[quantity];
    }
  }
}
