// The event-driven engine (src/grainflow/edmd/edmd_engine.hpp) against theory: conservation laws of
// an elastic gas, no interpenetration, a bouncing ball's apex heights, relaxation to a Maxwellian,
// the equations of state of hard spheres (Carnahan-Starling) and hard discs (Henderson), and a
// 20-degree chute that must run 10^7 events without stalling (Campbell 1982 section 2.14.2).
//
// Units: diameter 1, mass 1 (density 6/pi in 3D, 4/pi per area in 2D), temperature 1, fixed seeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/edmd/edmd_engine.hpp"
#include "test_support.hpp"

#include "elastic_gas_case.hpp"
#include "incline_case.hpp"

using namespace grainflow;
using namespace grainflow::edmd;

namespace {

// Run lengths: the issue's figures in optimised builds; a tenth (a half for the equation-of-state
// blocks) in unoptimised ones (the Debug preset with AddressSanitizer and UBSan runs these unit
// tests ~20 times slower), where the same physics is checked over shorter runs.
#ifdef NDEBUG
constexpr double kRunScale = 1.0;
#else
constexpr double kRunScale = 0.1;
#endif

// An elastic gas of n^dim unit particles at packing fraction phi in a periodic box (elastic_gas_case.hpp).
std::string gas_case(int dim, int n, double phi, double tangential, int seed) {
  return test::elastic_gas_case({dim, n, phi, 1.0, tangential, false, seed});
}

template <int Dim>
EdmdEngine<Dim> engine_from(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return EdmdEngine<Dim>(build_edmd_state(load_case_from_string(text, "edmd_test.toml", overrides)));
}

double kinetic_energy(const EdmdState& s) {  // translational + rotational
  const ParticleStore& p = s.particles;
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    e += 0.5 * p.mass[i] * norm2(p.velocity[i]) + 0.5 * norm2(p.angular_velocity[i]) / p.inv_inertia[i];
  return e;
}

double sum_mv2(const EdmdState& s) {  // sum m v^2 (translational)
  double e = 0.0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) e += s.particles.mass[i] * norm2(s.particles.velocity[i]);
  return e;
}

Vec3 momentum(const EdmdState& s) {
  Vec3 p;
  for (std::size_t i = 0; i < s.particles.size(); ++i) p += s.particles.mass[i] * s.particles.velocity[i];
  return p;
}

double momentum_scale(const EdmdState& s) {  // sum m |v|
  double m = 0.0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) m += s.particles.mass[i] * norm(s.particles.velocity[i]);
  return m;
}

// Largest overlap (r_i + r_j - |x_i - x_j|) / (r_i + r_j) over all pairs (minimum image), and the
// largest penetration of a wall (r - distance to the wall) / r. All particles must be current.
double max_relative_overlap(const EdmdState& s) {
  const ParticleStore& p = s.particles;
  double worst = -1.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      const double sigma = p.radius[i] + p.radius[j];
      worst = std::max(worst, 1.0 - norm(s.box.minimum_image(p.position[i], p.position[j])) / sigma);
    }
    for (const EdmdWall& w : s.walls)
      worst = std::max(worst, 1.0 - w.inward * (p.position[i][w.axis] - w.at(s.time)) / p.radius[i]);
  }
  return worst;
}

// Round-off bound for overlaps: positions of magnitude L ~ 10-40 carry ~eps L = 1e-14 absolute
// error after each of the many updates of a particle (lazy advance, wrapping); 1e-9 of a diameter
// is 10^4-10^5 times that and still 10^8 times smaller than the O(1) overlaps of a particle passing
// through another (Campbell section 2.14.1).
constexpr double kOverlapTolerance = 1e-9;

// ---------------------------------------------------------------------------------------------
// Neighbour lists (the path taken without gravity, Lees–Edwards or servo) against the cell search:
// the same collisions in the same order, so the same states until round-off (the two paths wrap
// positions at different times) is amplified by the chaos of the gas, after a few collisions per
// particle; and, with walls, no overlaps and energy kept over a longer run.

template <int Dim>
void check_lists_follow_cells(const test::ElasticGas& g, double t_end) {
  const CaseConfig c = load_case_from_string(test::elastic_gas_case(g), "edmd_test.toml");
  EdmdEngine<Dim> lists(build_edmd_state(c)), cells(build_edmd_state(c), false);
  ASSERT_TRUE(lists.neighbor_lists());
  ASSERT_FALSE(cells.neighbor_lists());
  lists.advance_to(t_end);
  cells.advance_to(t_end);
  const ParticleStore& a = lists.state().particles;
  const ParticleStore& b = cells.state().particles;
  // Each engine stores its particles in the order of its own cells: match them by id.
  std::vector<std::size_t> where(b.size());
  for (std::size_t k = 0; k < b.size(); ++k) where[static_cast<std::size_t>(b.id[k])] = k;
  double worst = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::size_t k = where[static_cast<std::size_t>(a.id[i])];
    worst = std::max(worst, norm(lists.state().box.minimum_image(a.position[i], b.position[k])));
    worst = std::max(worst, norm(a.velocity[i] - b.velocity[k]));
  }
  std::printf("  %dD, %zu particles, walls %d: %lld collisions (%lld wall) by t = %g; largest difference %.2e\n", Dim,
              a.size(), g.walls, lists.counters().collisions, lists.counters().wall_collisions, t_end, worst);
  EXPECT_GT(lists.counters().collisions, static_cast<long long>(a.size()));
  EXPECT_EQ(lists.counters().collisions, cells.counters().collisions);
  EXPECT_EQ(lists.counters().wall_collisions, cells.counters().wall_collisions);
  EXPECT_LT(worst, 1e-8);
}

TEST(EdmdNeighbourLists, FollowTheCellSearch3D) { check_lists_follow_cells<3>({3, 10, 0.3, 1.0, -1.0, false, 3}, 0.3); }
TEST(EdmdNeighbourLists, FollowTheCellSearch3DDenseRough) {
  check_lists_follow_cells<3>({3, 10, 0.45, 1.0, 1.0, false, 4}, 0.15);
}
TEST(EdmdNeighbourLists, FollowTheCellSearch3DWalls) {
  check_lists_follow_cells<3>({3, 10, 0.3, 1.0, -1.0, true, 5}, 0.3);
}
TEST(EdmdNeighbourLists, FollowTheCellSearch2D) { check_lists_follow_cells<2>({2, 30, 0.5, 1.0, -1.0, false, 6}, 0.6); }
TEST(EdmdNeighbourLists, FollowTheCellSearch2DWalls) {
  check_lists_follow_cells<2>({2, 30, 0.3, 1.0, 1.0, true, 7}, 1.5);
}

TEST(EdmdNeighbourLists, WalledGasKeepsEnergyAndNeverOverlaps) {
  EdmdEngine<3> e = engine_from<3>(test::elastic_gas_case({3, 10, 0.4, 1.0, -1.0, true, 8}));
  ASSERT_TRUE(e.neighbor_lists());
  const double e0 = kinetic_energy(e.state());
  double worst_energy = 0.0, worst_overlap = -1.0;
  for (int k = 1; k <= 40; ++k) {
    e.advance_to(k * kRunScale);
    worst_energy = std::max(worst_energy, std::fabs(kinetic_energy(e.state()) / e0 - 1.0));
    worst_overlap = std::max(worst_overlap, max_relative_overlap(e.state()));
  }
  std::printf("  walled gas: %lld collisions, %lld wall, %lld list rebuilds; max |dE/E| %.2e, max overlap %.2e\n",
              e.counters().collisions, e.counters().wall_collisions, e.counters().list_rebuilds, worst_energy,
              worst_overlap);
  EXPECT_GT(e.counters().wall_collisions, 0);
  EXPECT_GT(e.counters().list_rebuilds, 0);
  EXPECT_LT(worst_energy, 1e-9);
  EXPECT_LT(worst_overlap, kOverlapTolerance);
}

// ---------------------------------------------------------------------------------------------
// Elastic gas: energy to 1e-9 relative over 10^6 collisions, momentum to round-off, no overlaps.

template <int Dim>
void check_elastic_gas(const std::string& text, long long target_collisions, double chunk) {
  EdmdEngine<Dim> e = engine_from<Dim>(text);
  EXPECT_TRUE(e.neighbor_lists());  // straight flights in a periodic box
  const double e0 = kinetic_energy(e.state());
  const Vec3 p0 = momentum(e.state());
  const double pscale = momentum_scale(e.state());
  double worst_energy = 0.0, worst_momentum = 0.0, worst_overlap = -1.0;
  double t = 0.0;
  int outputs = 0;
  const auto start = std::chrono::steady_clock::now();
  while (e.counters().collisions < target_collisions && outputs < 400) {
    t += chunk;
    e.advance_to(t);
    ++outputs;
    worst_energy = std::max(worst_energy, std::fabs(kinetic_energy(e.state()) / e0 - 1.0));
    worst_momentum = std::max(worst_momentum, norm(momentum(e.state()) - p0) / pscale);
    worst_overlap = std::max(worst_overlap, max_relative_overlap(e.state()));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& k = e.counters();
  std::printf(
      "  %dD elastic gas, %zu particles: %lld collisions (%lld events) in t = %g, %.2f s (%.3g collisions/s); "
      "max |dE/E| %.2e, max |dP|/sum m|v| %.2e, max overlap %.2e diameters, %d checks\n",
      Dim, e.state().particles.size(), k.collisions, k.events, t, seconds, k.collisions / seconds, worst_energy,
      worst_momentum, worst_overlap, outputs);
  ASSERT_GE(k.collisions, target_collisions);
  EXPECT_EQ(k.wall_collisions, 0);
  // Energy: each collision conserves it exactly but for a few ulps, with random signs: ~sqrt(10^6)
  // 1e-16 = 1e-13 expected; the issue's bound is 1e-9.
  EXPECT_LT(worst_energy, 1e-9);
  // Momentum: each impulse is applied +J / -J, so only rounding of m v +- J remains: a random walk
  // of ~1e-16 per collision relative to sum m|v|, ~1e-14 after 10^6. 1e-12 is round-off;
  // anything physical (a missed partner update, a wrong mass) is >= 1e-3.
  EXPECT_LT(worst_momentum, 1e-12);
  EXPECT_LT(worst_overlap, kOverlapTolerance);
}

TEST(EdmdElasticGas, Spheres3DConserveEnergyAndMomentumOver1e6Collisions) {
  // 1000 smooth spheres at packing fraction 0.3 (~5100 collisions per unit time): 10^6 collisions
  // in t ~ 200, checked at 40 output times (every 5 time units, ~25 collisions per particle).
  check_elastic_gas<3>(gas_case(3, 10, 0.3, -1.0, 3), static_cast<long long>(1e6 * kRunScale), 5.0);
}

TEST(EdmdElasticGas, RoughDiscs2DConserveEnergyAndMomentumOver1e6Collisions) {
  // 1024 perfectly elastic rough discs (tangential restitution +1: spins are exchanged with
  // translation; energy counted with rotation) at packing fraction 0.4.
  check_elastic_gas<2>(gas_case(2, 32, 0.4, 1.0, 4), static_cast<long long>(1e6 * kRunScale), 5.0);
}

// ---------------------------------------------------------------------------------------------
// A ball bouncing on a floor under gravity: apex heights in the ratio e^2.

// One ball (d = 1, density 1) from `file` above a floor (wall at y = 0, restitution e_wall, the
// given condition) under g = 9.81 in a 3 x 10 (x 3) box, periodic sideways; `collision` holds
// extra [collision] keys.
std::string ball_on_floor_case(int dim, const std::string& file, double e_wall, const std::string& condition,
                               const std::string& collision) {
  char text[2048];
  std::snprintf(text, sizeof text, R"([engine]
kind = "edmd"
dimension = %d
[domain]
lo = [0.0, 0.0, 0.0]
hi = [3.0, 10.0, 3.0]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.0, -9.81, 0.0]
[[species]]
name = "ball"
diameter = 1.0
density = 1.0
count = 0
[particles]
init = "file"
file = "%s"
[collision]
restitution = 0.5
%s
[walls.ylo]
restitution = %.17g
condition = "%s"
[run]
duration = 10.0
)",
                dim, file.c_str(), collision.c_str(), e_wall, condition.c_str());
  return text;
}

template <int Dim>
void check_bouncing_ball(const std::string& condition) {
  // One particle (R = 0.5) dropped from 2 (gap below it) with a horizontal velocity, g = 9.81,
  // wall restitution e = 0.8; rolling_speed and elastic_speed 0 (set explicitly: under gravity
  // rolling_speed defaults to 1e-4 sqrt(g R), harmless here but not the point), so every bounce is a
  // plain restitution: after bounce k the flight energy (gap + vy^2 / 2g) is e^(2k) h0. Between
  // bounces free flight is an exact parabola and each bounce a few operations: 1e-12 relative.
  const double e = 0.8, g = 9.81, h0 = 2.0, R = 0.5;
  test::ParticleFile file("ball.csv", "ball,1.5,2.5,1.5,0.3,0.0,0.0\n");
  const std::string text =
      ball_on_floor_case(Dim, file.path(), e, condition, "rolling_speed = 0.0\nelastic_speed = 0.0");
  EdmdEngine<Dim> engine = engine_from<Dim>(text);
  const auto& p = engine.state().particles;
  ASSERT_EQ(p.size(), 1u);
  ASSERT_DOUBLE_EQ(p.position[0].y - R, h0);
  std::vector<double> apex;
  long long bounces = 0;
  double t = 0.0;
  // 12 bounces take t ~ 0.64 (1 + 2 (0.8 + ... + 0.8^11)) = 4.8; sampled every 1e-3.
  while (bounces < 12 && t < 10.0) {
    t += 1e-3;
    engine.advance_to(t);
    if (engine.counters().wall_collisions > bounces) {
      ASSERT_EQ(engine.counters().wall_collisions, bounces + 1) << "two bounces within one sample";
      bounces = engine.counters().wall_collisions;
      apex.push_back(p.position[0].y - R + p.velocity[0].y * p.velocity[0].y / (2 * g));
    }
  }
  ASSERT_EQ(bounces, 12);
  EXPECT_NEAR(apex[0] / h0, e * e, 1e-12);
  for (std::size_t k = 1; k < apex.size(); ++k) EXPECT_NEAR(apex[k] / apex[k - 1], e * e, 1e-12) << "bounce " << k + 1;
  EXPECT_NEAR(apex.back() / h0, std::pow(e, 24), 1e-12);
  EXPECT_EQ(engine.counters().rolling_starts, 0);
  EXPECT_GE(p.position[0].y, R * (1.0 - kOverlapTolerance));
  if (condition == "smooth") {
    EXPECT_NEAR(p.velocity[0].x, 0.3, 1e-15);  // a smooth floor keeps it
  }
}

TEST(EdmdBouncingBall, ApexHeightsFallByESquared2DSmooth) { check_bouncing_ball<2>("smooth"); }
TEST(EdmdBouncingBall, ApexHeightsFallByESquared3DRough) { check_bouncing_ball<3>("rough"); }

// ---------------------------------------------------------------------------------------------
// Rolling (Campbell section 2.14.2): a particle whose rebound from the floor is slower than
// rolling_speed rolls along it with acceleration g sin(alpha) / (1 + beta) and omega = -u / R on a
// rough floor, or slides with g sin(alpha) and its spin untouched on a smooth one.

template <int Dim>
void check_rolling(const std::string& condition) {
  // A unit disc/sphere (R = 1, m = 1) dropped from a gap of 0.1 onto a floor tilted 20 degrees
  // (g = 1), wall restitution 0.5, rolling_speed 0.05: the normal impact speed 0.43 halves at each
  // bounce, so the 4th rebound (0.027) is too slow and the particle rolls from t ~ 1.3 on. Over
  // the next 2 time units the motion is the exact uniformly accelerated one: velocity, unwrapped
  // displacement and spin agree with it to round-off (1e-12).
  const double alpha = 20.0 * M_PI / 180.0, q = Dim == 2 ? 0.5 : 0.4, R = 1.0;
  test::ParticleFile file("roller.csv", "ball,5.0,1.1,2.0,0.0,0.0,0.0\n");
  const std::string text = test::incline_case(Dim, 20.0, alpha, file.path(), condition, 10.0);
  EdmdEngine<Dim> e = engine_from<Dim>(text);
  const auto& p = e.state().particles;
  ASSERT_NEAR(p.mass[0], 1.0, 1e-15);
  double t = 0.0;
  while (e.counters().rolling_starts == 0 && t < 5.0) e.advance_to(t += 0.01);
  ASSERT_EQ(e.counters().rolling_starts, 1) << "never started rolling";
  EXPECT_GE(e.counters().wall_collisions, 3);
  const double u1 = p.velocity[0].x, x1 = e.state().box.unwrapped(p.position[0], p.image[0]).x;
  const Vec3 w1 = p.angular_velocity[0];
  const double dt = 2.0;
  e.advance_to(t + dt);
  const bool smooth = condition == "smooth";
  const double a = std::sin(alpha) / (smooth ? 1.0 : 1.0 + q);
  const double u2 = p.velocity[0].x, x2 = e.state().box.unwrapped(p.position[0], p.image[0]).x;
  EXPECT_NEAR(u2 - u1, a * dt, 1e-12);
  EXPECT_NEAR(x2 - x1, u1 * dt + 0.5 * a * dt * dt, 1e-12);
  EXPECT_EQ(p.velocity[0].y, 0.0);  // on the floor, not bouncing
  EXPECT_NEAR(p.position[0].y, R, 1e-15);
  EXPECT_EQ(e.counters().rolling_starts, 1);  // no further bounces
  if (smooth) {
    EXPECT_EQ(p.angular_velocity[0], w1);  // sliding: spin untouched
  } else {
    EXPECT_NEAR(p.angular_velocity[0].z, -u2 / R, 1e-12);  // rolling without slip
    EXPECT_NEAR(w1.z, -u1 / R, 1e-12);
  }
}

TEST(EdmdRolling, RollsDownARoughFloorAtGSinAlphaOver1PlusBeta2D) { check_rolling<2>("rough"); }
TEST(EdmdRolling, RollsDownARoughFloorAtGSinAlphaOver1PlusBeta3D) { check_rolling<3>("rough"); }
TEST(EdmdRolling, SlidesDownASmoothFloorAtGSinAlpha) { check_rolling<3>("smooth"); }

// ---------------------------------------------------------------------------------------------
// A disc dropped onto a disc resting on the floor (gravity 1, R = 0.5, e = 0.7, rough): the lower
// disc rolls (its floor rebounds are below rolling_speed), the upper one lands on it off-centre and
// rolls off it. Hard discs must never interpenetrate beyond round-off, whatever the collision
// cascade between the upper disc, the rolling disc and the floor (Campbell section 2.14.1-2). Run
// with the defaults (no TC model) and with the TC model; overlaps checked every 0.01 up to t = 5.

void check_disc_on_rolling_disc(const std::string& extra) {
  test::ParticleFile file("stack.csv", "p,4.0,0.5,0.0,0,0,0\np,4.1,1.8,0.0,0,0,0\n");
  const std::string text = R"([engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [8.0, 10.0, 1.0]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.0, -1.0, 0.0]
[[species]]
name = "p"
diameter = 1.0
density = 1.2732395447351628
count = 0
[particles]
init = "file"
file = ")" + file.path() + R"("
[collision]
restitution = 0.7
roughness = "rough"
)" + extra + R"(
[run]
duration = 5.0
)";
  EdmdEngine<2> e = engine_from<2>(text);
  double worst = -1.0, worst_time = 0.0;
  for (int k = 1; k <= 500; ++k) {
    e.advance_to(0.01 * k);
    const double overlap = max_relative_overlap(e.state());
    if (overlap > worst) worst = overlap, worst_time = 0.01 * k;
  }
  EXPECT_LT(worst, kOverlapTolerance) << "overlap of " << worst << " diameters at t = " << worst_time << " ("
                                      << e.counters().collisions << " collisions, " << e.counters().rolling_starts
                                      << " rolling starts)";
}

TEST(EdmdNoOverlap, DiscDroppedOnARollingDiscWithDefaults) { check_disc_on_rolling_disc(""); }
TEST(EdmdNoOverlap, DiscDroppedOnARollingDiscWithTC) { check_disc_on_rolling_disc("contact_duration = 1e-4"); }

// ---------------------------------------------------------------------------------------------
// Relaxation to a Maxwellian.

TEST(EdmdElasticGas, RelaxesToAMaxwellian) {
  // 4096 smooth spheres (16^3 simple cubic lattice, packing fraction 0.2), all with the same speed
  // sqrt(3) in random directions: each velocity component is then uniform on [-sqrt 3, sqrt 3]
  // (kurtosis 1.8). After ~25 collisions per particle an elastic gas must be Maxwellian:
  //  - kurtosis <v^4>/<v^2>^2 of one component = 3. The sampling s.d. of the kurtosis of n Gaussian
  //    values is sqrt(24/n); with the 3 x 4096 components of one snapshot n = 12288 gives 0.044,
  //    and the mean over 10 snapshots (2 collision times apart, so not independent: no credit
  //    taken) has no larger s.d.: tolerance 4 s.d. = 0.18, far from the initial 1.8.
  //  - chi-square of one snapshot's 12288 components in 30 equiprobable bins of the Gaussian with
  //    the measured variance (28 degrees of freedom): below 56.9, the p = 0.001 critical value.
  //    The initial state gives thousands.
  const int n = 16;
  const double phi = 0.2, spacing = std::pow(M_PI / 6.0 / phi, 1.0 / 3.0);
  std::string rows;
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> gauss;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        Vec3 v{gauss(rng), gauss(rng), gauss(rng)};
        v = v * (std::sqrt(3.0) / norm(v));
        char row[256];
        std::snprintf(row, sizeof row, "p,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", (i + 0.5) * spacing,
                      (j + 0.5) * spacing, (k + 0.5) * spacing, v.x, v.y, v.z);
        rows += row;
      }
  test::ParticleFile file("maxwell.csv", rows);
  std::string text = gas_case(3, n, phi, -1.0, 1);
  text.replace(text.find("count = 4096"), 12, "count = 0");
  text.replace(text.find("init = \"lattice\""), 16, "init = \"file\"\nfile = \"" + file.path() + "\"");
  EdmdEngine<3> e = engine_from<3>(text);
  ASSERT_EQ(e.state().particles.size(), 4096u);

  auto components = [&] {
    std::vector<double> c;
    const Vec3 mean = momentum(e.state()) * (1.0 / 4096);
    for (const Vec3& v : e.state().particles.velocity)
      for (int a = 0; a < 3; ++a) c.push_back(v[a] - mean[a]);
    return c;
  };
  auto kurtosis = [](const std::vector<double>& c) {
    double m2 = 0, m4 = 0;
    for (double x : c) m2 += x * x, m4 += x * x * x * x;
    m2 /= c.size();
    m4 /= c.size();
    return m4 / (m2 * m2);
  };
  auto chi_square = [](const std::vector<double>& c) {
    double m2 = 0;
    for (double x : c) m2 += x * x;
    const double sd = std::sqrt(m2 / c.size());
    const int bins = 30;
    std::vector<int> count(bins, 0);
    for (double x : c) {  // equiprobable bins: Phi(x / sd) in [k/bins, (k+1)/bins)
      const double cdf = 0.5 * std::erfc(-x / sd / std::sqrt(2.0));
      ++count[std::min(bins - 1, static_cast<int>(cdf * bins))];
    }
    const double expected = static_cast<double>(c.size()) / bins;
    double chi2 = 0;
    for (int k : count) chi2 += (k - expected) * (k - expected) / expected;
    return chi2;
  };
  EXPECT_NEAR(kurtosis(components()), 1.8, 0.1);  // the start is far from Gaussian
  EXPECT_GT(chi_square(components()), 1000.0);

  // Collision time per particle at phi = 0.2, T = 1: ~1/4.8 (Enskog). Relax for t = 5 (~25
  // collisions per particle), then sample 10 snapshots 0.4 apart.
  e.advance_to(5.0);
  double mean_kurtosis = 0.0;
  for (int s = 1; s <= 10; ++s) {
    e.advance_to(5.0 + 0.4 * s);
    mean_kurtosis += kurtosis(components()) / 10;
  }
  const double chi2 = chi_square(components());
  std::printf("  Maxwellian: %lld collisions, kurtosis %.4f (Gaussian 3), chi-square %.1f (28 dof)\n",
              e.counters().collisions, mean_kurtosis, chi2);
  EXPECT_GT(e.counters().collisions, 20 * 4096 / 2);
  EXPECT_NEAR(mean_kurtosis, 3.0, 4 * std::sqrt(24.0 / 12288));
  EXPECT_LT(chi2, 56.9);
}

// ---------------------------------------------------------------------------------------------
// Equations of state: pressure from the collisional virial.
//
// For hard particles the virial theorem gives P V d = sum m v^2 + (1/dt) sum_collisions r_ij . J_i
// (r_ij from j to i at contact, J_i the impulse on i; EventCounters::virial accumulates the sum).
// With kT = sum m v^2 / (d N) (conserved: the gas is elastic and smooth) the compressibility factor
// is Z = P V / (N k T) = 1 + virial_rate / sum m v^2, independent of the box and the masses.
//
// References: Carnahan & Starling, J. Chem. Phys. 51, 635 (1969): Z = (1 + phi + phi^2 - phi^3) /
// (1 - phi)^3, within ~0.1-0.3% of simulations for phi <= 0.3 (Kolafa et al. 2004); Henderson,
// Mol. Phys. 30, 971 (1975): Z = (1 + phi^2/8) / (1 - phi)^2 for discs, within ~0.5% of
// simulations for phi <= 0.5 (Mulero et al. 2009). Tolerance: 1% of Z (the equations' accuracy the
// issue quotes, with finite-size effects of O(1/N) = 0.1-0.2% inside it) plus 3 standard errors of
// the mean over 20 blocks. The standard error itself must stay below 0.5% of Z so that the check
// means something.
//
// Cross-check (not asserted; 5 seeds of 10^6 collisions each, run while writing this test): the
// engine gives Z = 3.985 +- 0.001 for spheres at phi = 0.3 and 4.106 +- 0.002 for discs at 0.5,
// where the virial series summed to its 10th coefficient (Clisby & McCoy 2006; tail < 0.1%) gives
// 3.984 and 4.106: Carnahan-Starling is 0.26% low and Henderson 0.45% high there, both within the
// 1% they are held to here.

struct Compressibility {
  double z, standard_error;
  long long collisions;
};

template <int Dim>
Compressibility measure_compressibility(const std::string& text, long long collisions_per_block) {
  EdmdEngine<Dim> e = engine_from<Dim>(text);
  const double n = static_cast<double>(e.state().particles.size());
  // Equilibrate: the lattice melts and the pair structure settles within ~10 collisions per
  // particle; the collision rate found there sets the block length.
  double t = 0.0;
  while (e.counters().collisions < 5 * n) e.advance_to(t += 0.1);
  const double rate = e.counters().collisions / t;
  const double block = collisions_per_block / rate;
  const double mv2 = sum_mv2(e.state());
  std::vector<double> z;
  for (int b = 0; b < 20; ++b) {
    const double virial = e.counters().virial;
    e.advance_to(t += block);
    z.push_back(1.0 + (e.counters().virial - virial) / block / mv2);
  }
  EXPECT_NEAR(sum_mv2(e.state()) / mv2, 1.0, 1e-11);  // elastic: T did not drift
  double mean = 0.0, var = 0.0;
  for (double x : z) mean += x / z.size();
  for (double x : z) var += (x - mean) * (x - mean) / (z.size() - 1);
  return {mean, std::sqrt(var / z.size()), e.counters().collisions};
}

void check_against(const Compressibility& m, double reference, const char* what, double phi) {
  const double tolerance = 0.01 * reference + 3.0 * m.standard_error;
  std::printf("  %s phi = %.2f: Z = %.4f +- %.4f (%lld collisions), equation of state %.4f, deviation %+.2f%%\n", what,
              phi, m.z, m.standard_error, m.collisions, reference, 100.0 * (m.z / reference - 1.0));
  EXPECT_LT(m.standard_error, 0.005 * reference) << what << " phi = " << phi;
  EXPECT_NEAR(m.z, reference, tolerance) << what << " phi = " << phi;
}

TEST(EdmdEquationOfState, HardSpheresMatchCarnahanStarling) {
  // 1000 spheres; 20 blocks of 10^4 collisions (20 per particle) after equilibration.
  for (double phi : {0.1, 0.2, 0.3}) {
    const Compressibility m =
        measure_compressibility<3>(gas_case(3, 10, phi, -1.0, 7), kRunScale == 1.0 ? 10'000 : 5'000);
    const double cs = (1 + phi + phi * phi - phi * phi * phi) / std::pow(1 - phi, 3);
    check_against(m, cs, "hard spheres", phi);
  }
}

TEST(EdmdEquationOfState, HardDiscsMatchHenderson) {
  // 1024 discs; 20 blocks of 10^4 collisions.
  for (double phi : {0.2, 0.35, 0.5}) {
    const Compressibility m =
        measure_compressibility<2>(gas_case(2, 32, phi, -1.0, 8), kRunScale == 1.0 ? 10'000 : 5'000);
    const double henderson = (1 + phi * phi / 8) / ((1 - phi) * (1 - phi));
    check_against(m, henderson, "hard discs", phi);
  }
}

// ---------------------------------------------------------------------------------------------
// Campbell's chute at 20 degrees: 10^7 events without stalling.

constexpr const char* kChute = R"([engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [9.6, 80.0, 1.0]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.3420201433256687, -0.9396926207859084, 0.0]   # g = 1, 20 degrees
[[species]]
name = "disc"
diameter = 2.0
density = 0.3183098861837907
count = 40
[particles]
init = "lattice"
region_hi = [9.6, 24.0, 1.0]
lattice_spacing = 1.2
lattice_jitter = 0.3
initial_velocity = [3.0, 0.0, 0.0]
initial_temperature = 0.01
seed = 1982
[collision]
restitution = 0.6
roughness = "rough"
inertia_factor = 0.5
rolling_speed = 1.0e-4
contact_duration = 1.0e-4
[walls.ylo]
restitution = 0.8
condition = "rough"
[run]
duration = 500.0
)";

TEST(EdmdChute, TwentyDegreesRuns1e7EventsWithoutStalling) {
  // cases/campbell1982/chute_30deg.toml tilted to 20 degrees (40 rough discs, e_p = 0.6,
  // e_w = 0.8, rolling below 1e-4 sqrt(gR), TC duration 1e-4 sqrt(R/g)). The flow accelerates,
  // then (at this angle) comes to rest on the rough floor within t ~ 200: a dense bed under
  // gravity, where inelastic collapse and endless wall bounces would stop the clock of a naive
  // event-driven code. advance_to throws RunError when time stops; here every unit of time must
  // complete, the run must reach 10^7 events, and the state must stay physical (no overlaps, no
  // particle through the floor, energy not created).
  EdmdEngine<2> e = engine_from<2>(kChute);
  const double initial_energy = kinetic_energy(e.state());
  double t = 0.0, max_energy = initial_energy;
  const long long target = static_cast<long long>(1e7 * kRunScale);
  const auto start = std::chrono::steady_clock::now();
  try {
    while (e.counters().events < target && t < 5000.0) {
      e.advance_to(t += 1.0);
      ASSERT_EQ(e.state().time, t);
      if (static_cast<long>(t) % 10 == 0) {
        EXPECT_LT(max_relative_overlap(e.state()), kOverlapTolerance) << "t = " << t;
        max_energy = std::max(max_energy, kinetic_energy(e.state()));
      }
    }
  } catch (const RunError& error) {
    FAIL() << "the chute stalled at t = " << e.state().time << " after " << e.counters().events
           << " events: " << error.what();
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& k = e.counters();
  std::printf(
      "  20-degree chute: %lld events (%lld collisions, %lld wall, %lld rolling starts, %lld stale) to "
      "t = %g in %.2f s: %.3g events/s\n",
      k.events, k.collisions, k.wall_collisions, k.rolling_starts, k.stale, t, seconds, k.events / seconds);
  ::testing::Test::RecordProperty("events_per_second", std::to_string(k.events / seconds));
  EXPECT_GE(k.events, target);
  EXPECT_GT(k.collisions, target / 2);  // mostly real collisions, not bookkeeping
  EXPECT_LT(max_relative_overlap(e.state()), kOverlapTolerance);
  EXPECT_TRUE(std::isfinite(max_energy));
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// A run that cannot advance simulated time must stop with a message, not hang. A ball bouncing on
// a floor with e = 0.8 and nothing to stop it (no rolling state, no TC model) bounces ever faster:
// dropped through a gap h = 2 it lands at t0 = sqrt(2h/g), bounce k lasts 2 t0 e^k, so the bounces
// pile up at t = t0 (1 + 2e / (1 - e)) = 9 t0 = 5.747 s (Zeno), and after ~160 bounces the
// intervals are below the resolution of t. The engine must say so at the accumulation point (its
// progress check needs time to move by 1e-9 of itself per ~1000 events, i.e. it stops within
// ~1e-8 s of it; 1e-6 allows for that) instead of crawling for ever.
TEST(EdmdStall, ZenoBouncesStopTheRunWithAMessage) {
  test::ParticleFile file("zeno.csv", "ball,1.5,2.5,1.5,0.0,0.0,0.0\n");
  const std::string text =
      ball_on_floor_case(3, file.path(), 0.8, "smooth", "rolling_speed = 0.0\ncontact_duration = 0.0");
  EdmdEngine<3> engine = engine_from<3>(text);
  try {
    engine.advance_to(10.0);
    FAIL() << "the run reached t = 10 s through a Zeno point at 5.747 s";
  } catch (const RunError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("simulated time"), std::string::npos) << message;
    EXPECT_NEAR(engine.state().time, 9.0 * std::sqrt(2.0 * 2.0 / 9.81), 1e-6);
  }
}

// Energy balance of a sheared cell: the top wall moves at U, walls and discs are rough and
// inelastic. Per wall collision the wall does work J . U on the particle (J its impulse), so over
// a run  Delta KE = sum J . U - dissipated, to rounding; and each collision's dissipation, measured
// in the frame where it is Galilean (the wall's, the pair's), is never negative.
class WallWork : public engine_api::CollisionObserver {
 public:
  explicit WallWork(const EdmdState& s) : s_(s) {}
  void on_pair(const engine_api::PairCollision& c) override {
    least_dissipated = std::min(least_dissipated, c.dissipated);
  }
  void on_wall(const engine_api::WallCollision& c) override {
    work += dot(c.impulse, s_.walls[c.wall].velocity);
    least_dissipated = std::min(least_dissipated, c.dissipated);
    ++collisions;
  }
  double work = 0.0, least_dissipated = 0.0;
  long collisions = 0;

 private:
  const EdmdState& s_;
};

TEST(EdmdEngine, ShearedCellEnergyBalanceAndNonNegativeDissipation) {
  const std::string text = R"(
[engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [9.6, 12.0, 1.0]
boundary = { x = "periodic", y = "wall", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "disc"
diameter = 2.0
density = 0.3183098861837907
count = 20
[particles]
init = "lattice"
lattice_spacing = 1.2
lattice_jitter = 0.3
initial_profile = "couette"
initial_temperature = 0.001
seed = 7
[collision]
restitution = 0.7
roughness = "rough"
contact_duration = 1.0e-4
[walls.ylo]
restitution = 0.8
condition = "rough"
[walls.yhi]
restitution = 0.8
condition = "no_slip"
velocity = [1.0, 0.0, 0.0]
[run]
duration = 200.0
)";
  EdmdEngine<2> e = engine_from<2>(text);
  WallWork observer(e.state());
  e.set_observer(&observer);
  const double start = kinetic_energy(e.state());
  e.advance_to(200.0);  // ~1 ms optimised: not shortened in the sanitizer build
  const double end = kinetic_energy(e.state());
  ASSERT_GT(observer.collisions, 20) << "too few wall collisions to test anything";
  ASSERT_GT(e.counters().collisions, 20);
  // Rounding: each collision's energies carry ~1e-16 relative error; a few thousand collisions.
  const double scale = std::fabs(observer.work) + e.counters().dissipated + start;
  EXPECT_NEAR(end - start, observer.work - e.counters().dissipated, 1e-10 * scale);
  EXPECT_GT(e.counters().dissipated, 0.0);
  EXPECT_GE(observer.least_dissipated, -1e-12 * scale);
}

// ---------------------------------------------------------------------------------------------
// The TC model's share of the collisions. Disc A (speed 1) hits B, which touches C at rest: with
// e = 0.5, A keeps 0.25 and B takes 0.75; B, having just collided, meets C at once: a TC collision,
// elastic and smooth, so B stops and C leaves at 0.75; A then meets the stopped B at once: a second
// TC collision (A 0, B 0.25), and nothing more. 2 of 3 collisions are TC ones; with the model off,
// none are (and the inelastic cascade takes more collisions).
void check_tc_share(double contact_duration, long long collisions, long long tc) {
  test::ParticleFile file("row.csv", "p,1.0,2.5,0.0,1,0,0\np,3.0,2.5,0.0,0,0,0\np,4.0,2.5,0.0,0,0,0\n");
  const std::string text = R"([engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [40.0, 5.0, 1.0]
boundary = { x = "periodic", y = "periodic", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "p"
diameter = 1.0
density = 1.0
count = 0
[particles]
init = "file"
file = ")" + file.path() + R"("
[collision]
restitution = 0.5
contact_duration = )" + std::to_string(contact_duration) +
                           R"(
[run]
duration = 5.0
)";
  EdmdEngine<2> e = engine_from<2>(text);
  e.advance_to(5.0);
  if (collisions > 0) {
    EXPECT_EQ(e.counters().collisions, collisions);
  }
  EXPECT_EQ(e.counters().tc_collisions, tc);
}

TEST(EdmdTcModel, CountsTheCollisionsItMakesElastic) {
  check_tc_share(0.01, 3, 2);
  check_tc_share(0.0, 0, 0);
}
