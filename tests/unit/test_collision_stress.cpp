// Stresses from an event-driven run's collisions (observe/collision_stress.hpp, observe/wall_stress.hpp,
// the engine's CollisionObserver): exact strip shares of branch vectors for a known collision, exact
// stresses for one disc bouncing between two walls, the virial pressure and n m T of an elastic gas,
// the symmetry of the collisional stress, a gas at rest pressing on its walls, and a disc rolling on
// an incline pressing with its weight.
//
// Units: diameter 1 and mass 1 unless stated; fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/edmd/edmd_engine.hpp"
#include "grainflow/observe/collision_stress.hpp"
#include "grainflow/observe/wall_stress.hpp"
#include "test_support.hpp"

#include "elastic_gas_case.hpp"
#include "incline_case.hpp"

using namespace grainflow;
using namespace grainflow::edmd;
using engine_api::CollisionObserver;
using engine_api::PairCollision;
using engine_api::WallCollision;
using observe::StressProfile;
using observe::StripGrid;
using observe::StripStress;
using observe::WallLoads;

namespace {

#ifdef NDEBUG
constexpr double kRunScale = 1.0;
#else
constexpr double kRunScale = 0.1;  // the sanitizer build runs ~20 times slower
#endif

constexpr int XX = 0, XY = 1, YX = 3, YY = 4;

double trace2(const observe::Tensor3& t) { return t[XX] + t[YY]; }

// Feeds one run's collisions to a stress profile and the wall loads over fixed strips (walls that do
// not move), as the run driver does, and samples every `dt`.
template <int Dim>
class Recorder : public CollisionObserver {
 public:
  Recorder(EdmdEngine<Dim>& e, const StripGrid& grid, double period = 0.0)
      : e_(e), grid_(grid), stress_(grid.count(), period), walls_(e.state().walls) {}

  void on_pair(const PairCollision& c) override { stress_.add(grid_, c); }
  void on_wall(const WallCollision& c) override {
    stress_.add(grid_, c);
    walls_.add(c, grid_.cross_section());
  }

  void run(double from, double to, double dt) {
    e_.advance_to(from);
    stress_.begin(grid_, e_.state().particles, from);
    virial_start_ = e_.counters().virial;
    e_.set_observer(this);
    const long steps = std::lround((to - from) / dt);
    for (long k = 1; k <= steps; ++k) {
      const double t = from + k * dt;
      e_.advance_to(t);
      const EdmdState& s = e_.state();
      e_.for_each_rolling([&](std::uint32_t i, int w, const Vec3& force) {
        Vec3 contact = s.particles.position[i];
        contact[s.walls[w].axis] = s.walls[w].at(t);
        stress_.add_contact_force(grid_, s.particles.position[i], contact, force, dt);
        walls_.add_rolling(w, force, dt, grid_.cross_section());
      });
      stress_.sample(grid_, s.particles, t);
      walls_.close_interval(dt);
    }
    e_.set_observer(nullptr);
  }

  std::vector<StripStress> strips(const Vec3& top_row = {}) const {
    return stress_.averages(e_.state().gravity, top_row);
  }
  std::vector<observe::WallLoad> walls() const { return walls_.averages(); }
  double virial() const { return e_.counters().virial - virial_start_; }
  const StressProfile& stress() const { return stress_; }

 private:
  EdmdEngine<Dim>& e_;
  StripGrid grid_;
  StressProfile stress_;
  WallLoads walls_;
  double virial_start_ = 0.0;
};

// n x n unit discs at area fraction phi, elastic, periodic along x and, with `walls`, between smooth
// elastic walls at y = 0 and L, else periodic along y too (elastic_gas_case.hpp).
std::string disc_gas(int n, double phi, double tangential, bool walls, int seed) {
  return test::elastic_gas_case({2, n, phi, 1.0, tangential, walls, seed});
}

// Unit-mass discs of diameter 1 from `file`, elastic between each other, between walls at y = 0 and
// `height` with the given restitution and condition, periodic along x (`width`), no gravity.
std::string walled_discs_case(double width, double height, const std::string& file, double wall_restitution,
                              const char* condition) {
  char text[1024];
  std::snprintf(text, sizeof text, R"([engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [%g, %g, 1.0]
boundary = { x = "periodic", y = "wall", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "disc"
diameter = 1.0
density = %.17g
count = 0
[particles]
init = "file"
file = "%s"
[collision]
restitution = 1.0
[walls.ylo]
restitution = %g
condition = "%s"
[walls.yhi]
restitution = %g
condition = "%s"
[run]
duration = 1.0
)",
                width, height, 4.0 / M_PI, file.c_str(), wall_restitution, condition, wall_restitution, condition);
  return text;
}

EdmdEngine<2> engine2(const std::string& text) {
  return EdmdEngine<2>(build_edmd_state(load_case_from_string(text, "stress_test.toml")));
}

double sum_mv2(const ParticleStore& p) {
  double s = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) s += p.mass[i] * norm2(p.velocity[i]);
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// A known collision: its branch vector's length in each strip decides its share, exactly.

TEST(StressProfileShares, BranchVectorSplitByLengthAndContactPointCounted) {
  const StripGrid grid(2, 1, 0.0, 4.0, 4, 2.0);  // strips 1 thick, 2 wide: measure 2
  ParticleStore none;
  StressProfile sp(4);
  sp.begin(grid, none, 0.0);
  PairCollision c;
  c.xi = {0.3, 2.5, 0.0};
  c.xj = {0.0, 0.5, 0.0};
  c.contact = {0.15, 1.5, 0.0};
  c.impulse = {1.0, 2.0, 0.0};
  c.dissipated = 0.25;
  sp.add(grid, c);
  WallCollision w;  // on the ylo wall: impulse carried from the contact point to the centre
  w.contact = {1.0, 0.0, 0.0};
  w.x = {1.0, 0.5, 0.0};
  w.impulse = {-0.5, 3.0, 0.0};
  sp.add(grid, w);
  sp.sample(grid, none, 2.0);
  const auto s = sp.averages({}, {});
  ASSERT_EQ(s.size(), 4u);
  const Vec3 r{0.3, 2.0, 0.0};
  const double share[4] = {0.25, 0.5, 0.25, 0.0};  // y from 0.5 to 2.5 over strips [0,1), [1,2), [2,3)
  const double per = 1.0 / (2.0 * 2.0);            // per measure and per time
  for (int k = 0; k < 4; ++k) {
    for (int a = 0; a < 2; ++a)
      for (int b = 0; b < 2; ++b) {
        double expected = share[k] * r[a] * c.impulse[b] * per;
        if (k == 0) expected += Vec3{0.0, 0.5, 0.0}[a] * w.impulse[b] * per;
        EXPECT_NEAR(s[k].collisional[a * 3 + b], expected, 1e-15) << "strip " << k << " component " << a << b;
        EXPECT_EQ(s[k].kinetic[a * 3 + b], 0.0);
      }
    EXPECT_EQ(s[k].collision_rate, k == 1 ? per : 0.0);  // the contact point lies in strip 1
    EXPECT_EQ(s[k].dissipation_rate, k == 1 ? 0.25 * per : 0.0);
  }
}

TEST(StressProfileShares, PeriodicAxisWrapsTheBranchVector) {
  const StripGrid grid(2, 1, 0.0, 4.0, 4, 2.0);
  ParticleStore none;
  StressProfile sp(4, 4.0);
  sp.begin(grid, none, 0.0);
  PairCollision c;  // i just above y = 0, j's image just below: 1/4 of the branch in strip 0, 3/4 in strip 3
  c.xi = {0.0, 0.25, 0.0};
  c.xj = {0.0, -0.75, 0.0};
  c.contact = {0.0, -0.25, 0.0};  // wraps to y = 3.75
  c.impulse = {0.0, 1.0, 0.0};
  sp.add(grid, c);
  sp.sample(grid, none, 1.0);
  const auto s = sp.averages({}, {});
  EXPECT_NEAR(s[0].collisional[YY], 0.25 * 1.0 / 2.0, 1e-15);
  EXPECT_NEAR(s[3].collisional[YY], 0.75 * 1.0 / 2.0, 1e-15);
  EXPECT_EQ(s[1].collisional[YY] + s[2].collisional[YY], 0.0);
  EXPECT_EQ(s[3].collision_rate, 0.5);
}

TEST(StressProfileShares, KineticPartAboutTheLongTermStripMean) {
  // Two particles with centres in strip 2 (y = 2.2 and 2.9), masses 1 and 3, sampled twice: the
  // kinetic stress is sum m (v - u)(v - u) / measure / samples about u = sum m v / sum m over both
  // samples; the momentum-change rate is that between begin and the last sample.
  const StripGrid grid(2, 1, 0.0, 4.0, 4, 2.0);
  ParticleStore p;
  p.resize(2);
  p.mass = {1.0, 3.0};
  p.position = {{0.5, 2.2, 0.0}, {1.5, 2.9, 0.0}};
  const std::vector<std::vector<Vec3>> samples = {{{1.0, 0.0, 0.0}, {-1.0, 2.0, 0.0}},
                                                  {{3.0, 0.0, 0.0}, {-1.0, 2.0, 0.0}}};
  p.velocity = samples[0];
  StressProfile sp(4);
  sp.begin(grid, p, 0.0);
  for (std::size_t n = 0; n < samples.size(); ++n) {
    p.velocity = samples[n];
    sp.sample(grid, p, 1.0 + n);
  }
  const auto s = sp.averages({}, {});
  Vec3 u;
  for (const auto& v : samples) u += (1.0 / 8.0) * (1.0 * v[0] + 3.0 * v[1]);  // total mass 8
  double k[9] = {};
  for (const auto& v : samples)
    for (int i = 0; i < 2; ++i) {
      const Vec3 dv = v[i] - u;
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) k[a * 3 + b] += p.mass[i] * dv[a] * dv[b] / (2.0 * 2.0);  // / measure / samples
    }
  for (int c = 0; c < 9; ++c) EXPECT_NEAR(s[2].kinetic[c], k[c], 1e-14) << c;
  EXPECT_NEAR(s[2].mean_velocity.x, u.x, 1e-15);
  EXPECT_NEAR(s[2].mean_velocity.y, u.y, 1e-15);
  EXPECT_NEAR(s[2].mass_density, 4.0 / 2.0, 1e-15);
  EXPECT_EQ(s[2].number, 2.0);
  // Momentum along x: 1 - 3 = -2 at the start, 3 - 3 = 0 at the end, 2 s apart: Campbell's rho u_t.
  EXPECT_NEAR(s[2].momentum_rate.x, 2.0 / 2.0 / 2.0, 1e-15);
  EXPECT_NEAR(s[2].momentum_rate.y, 0.0, 1e-15);
  EXPECT_EQ(s[0].number, 0.0);
}

// ---------------------------------------------------------------------------------------------
// One disc (R = 1/2, m = 1) bouncing along y between smooth elastic walls at y = 0 and 4 at speed
// 1, in a box 3 wide: the momentum flux through every plane is m v^2 / ((L - 2R) W) = 1/9. Near a
// wall it is carried by the wall impulses along the contact-centre segment, elsewhere by the disc
// itself; each strip's total must be 1/9 and so must each wall's normal stress. The collisions are
// exact (100 on each wall in 600 s, to round-off); the kinetic part is sampled every 1e-3 s, which resolves the
// 1 s spent per visit in a strip to 1e-3: hence the 2e-3 tolerance.

TEST(CollisionStress, DiscBouncingBetweenWallsCarriesAUniformFlux) {
  test::ParticleFile file("bouncer.csv", "disc,1.5,2.0,0.0,0.0,1.0,0.0\n");
  const std::string text = walled_discs_case(3.0, 4.0, file.path(), 1.0, "smooth");
  EdmdEngine<2> e = engine2(text);
  Recorder<2> rec(e, StripGrid(2, 1, 0.0, 4.0, 4, 3.0));
  const double periods = kRunScale == 1.0 ? 100.0 : 10.0;
  rec.run(0.0, 6.0 * periods, 1e-3);
  const double flux = 1.0 / 9.0;
  for (const auto& w : rec.walls()) {
    EXPECT_NEAR(w.normal_stress, flux, 1e-10 * flux);  // the walls' time sums 6e5 sample intervals
    EXPECT_EQ(w.shear_stress, 0.0);
    EXPECT_EQ(w.collisions, static_cast<long long>(periods));
  }
  const auto s = rec.strips();
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(s[k].total[YY], flux, 2e-3 * flux) << "strip " << k;
    EXPECT_EQ(s[k].total[XX], 0.0);
    EXPECT_EQ(s[k].total[XY], 0.0);
  }
  // The wall strips: half by collisions (1/18 exactly: 2 m v x R per 6 s over 3 x 1), half kinetic.
  EXPECT_NEAR(s[0].collisional[YY], flux / 2.0, 1e-12 * flux);
  EXPECT_NEAR(s[3].collisional[YY], flux / 2.0, 1e-12 * flux);
  EXPECT_EQ(s[1].collisional[YY], 0.0);
}

// ---------------------------------------------------------------------------------------------
// An elastic gas of 400 smooth discs at area fraction 0.3 in a periodic box, in 8 strips.

TEST(CollisionStress, ElasticGasMatchesTheVirialAndNmT) {
  EdmdEngine<2> e = engine2(disc_gas(20, 0.3, -1.0, false, 7));
  const PeriodicBox box = e.state().box;
  const double area = box.length(0) * box.length(1);
  Recorder<2> rec(e, StripGrid(2, 1, box.lo.y, box.hi.y, 8, box.length(0)), box.length(1));
  const double span = 200.0 * kRunScale;
  rec.run(5.0, 5.0 + span, 0.05);
  const auto s = rec.strips();
  const double measure = area / 8.0;
  double collisional = 0.0, kinetic = 0.0, drift = 0.0;
  for (const auto& k : s) {
    collisional += trace2(k.collisional) * measure * span;
    kinetic += trace2(k.kinetic) * measure;
    drift += k.mass_density * measure * norm2(k.mean_velocity);
    // Smooth discs: every impulse lies along its branch vector, so each collision's r J is symmetric.
    EXPECT_NEAR(k.collisional[XY], k.collisional[YX], 1e-12 * trace2(k.collisional));
  }
  // Every branch vector is shared out whole (wrapped at the periodic ends): the strips hold the
  // engine's virial sum r_ij . J_i to round-off.
  EXPECT_NEAR(collisional, rec.virial(), 1e-10 * std::fabs(rec.virial()));
  // Kinetic: sum m v^2 is conserved in an elastic smooth gas; the strips count it less only the
  // mass x (long-term strip mean velocity)^2, which is ~ T per strip over all samples (< 1e-2).
  const double mv2 = sum_mv2(e.state().particles);
  EXPECT_NEAR(kinetic + drift, mv2, 1e-9 * mv2);
  EXPECT_GT(kinetic, (1.0 - 1e-2) * mv2);
  // Per strip, the kinetic part is n m T (T = sum m v^2 / (2 N m) = 1 here, n the strip's number
  // density) and the total is isotropic, within 4 standard errors (for n m T, of the kinetic
  // trace: measuring n as well only removes the density's share of its scatter).
  const double temperature = mv2 / (2.0 * e.state().particles.size());
  for (const auto& k : s) {
    const double nmT = k.mass_density * temperature;
    EXPECT_NEAR(0.5 * trace2(k.kinetic), nmT, 2.0 * (k.kinetic_error[XX] + k.kinetic_error[YY]));
    EXPECT_NEAR(k.total[XX], k.total[YY], 4.0 * std::hypot(k.total_error[XX], k.total_error[YY]));
    EXPECT_NEAR(k.total[XY], 0.0, 4.0 * k.total_error[XY]);
    EXPECT_TRUE(std::isfinite(k.total_error[XX]));
  }
}

TEST(CollisionStress, RoughGasCollisionalStressIsSymmetricOnAverage) {
  // Elastic rough discs (tangential restitution +1): single collisions give r J with r not
  // parallel to J, but in equilibrium the mean spin vanishes and so does the antisymmetric part.
  EdmdEngine<2> e = engine2(disc_gas(20, 0.4, 1.0, false, 11));
  const PeriodicBox box = e.state().box;
  Recorder<2> rec(e, StripGrid(2, 1, box.lo.y, box.hi.y, 4, box.length(0)), box.length(1));
  rec.run(5.0, 5.0 + 200.0 * kRunScale, 0.05);
  double asymmetry = 0.0;
  for (const auto& k : rec.strips()) {
    EXPECT_NEAR(k.collisional[XY], k.collisional[YX],
                4.0 * std::hypot(k.collisional_error[XY], k.collisional_error[YX]));
    asymmetry += std::fabs(k.collisional[XY] - k.collisional[YX]);
  }
  EXPECT_GT(asymmetry, 0.0);  // not symmetric collision by collision, as smooth discs are
}

// ---------------------------------------------------------------------------------------------
// The same gas between smooth walls at y = 0 and L, at rest: the walls' normal stress equals the
// strips' P_yy next to them and everywhere (momentum balance), and the bulk pressure, within 4
// standard errors of the difference.

TEST(CollisionStress, GasAtRestPressesOnItsWallsWithItsPressure) {
  EdmdEngine<2> e = engine2(disc_gas(20, 0.3, -1.0, true, 3));
  const PeriodicBox box = e.state().box;
  Recorder<2> rec(e, StripGrid(2, 1, box.lo.y, box.hi.y, 8, box.length(0)));
  rec.run(5.0, 5.0 + 200.0 * kRunScale, 0.05);
  const auto walls = rec.walls();
  ASSERT_EQ(walls.size(), 2u);
  const auto s = rec.strips();
  for (const auto& w : walls) {
    ASSERT_TRUE(std::isfinite(w.normal_stress_error));
    EXPECT_NEAR(w.shear_stress, 0.0, 4.0 * w.shear_stress_error);  // smooth walls: no tangential impulse
    for (const auto& k : s)
      EXPECT_NEAR(k.total[YY], w.normal_stress, 4.0 * std::hypot(k.total_error[YY], w.normal_stress_error));
    for (int k : {3, 4})  // the middle strips, away from the walls' layering: isotropic
      EXPECT_NEAR(0.5 * trace2(s[k].total), w.normal_stress,
                  4.0 * std::hypot(s[k].total_error[XX], w.normal_stress_error));
  }
}

// ---------------------------------------------------------------------------------------------
// A unit disc rolling down a rough floor tilted 20 degrees (g = 1): the floor holds it with
// m g cos(alpha) and brakes it with m g sin(alpha) q / (1 + q) (q = 1/2), continuously. Its wall
// load and the strip it lies in carry exactly that (exact rolling motion, forces sampled).

TEST(CollisionStress, RollingDiscPressesWithItsWeight) {
  const double alpha = 20.0 * M_PI / 180.0, q = 0.5, width = 20.0;
  test::ParticleFile file("roller.csv", "ball,5.0,1.0,0.0,0.0,0.0,0.0\n");
  const std::string text = test::incline_case(2, width, alpha, file.path(), "rough", 1.0);
  EdmdEngine<2> e = engine2(text);
  double t = 0.0;
  while (e.counters().rolling_starts == 0 && t < 5.0) e.advance_to(t += 0.01);
  ASSERT_EQ(e.counters().rolling_starts, 1);
  const long long bounces = e.counters().wall_collisions;
  Recorder<2> rec(e, StripGrid(2, 1, 0.0, 4.0, 2, width));
  rec.run(t, t + 3.0, 0.01);
  ASSERT_EQ(e.counters().wall_collisions, bounces);  // rolling all along
  const auto w = rec.walls();
  const double normal = std::cos(alpha) / width, shear = -std::sin(alpha) * q / (1.0 + q) / width;
  EXPECT_NEAR(w[0].normal_stress, normal, 1e-12);
  EXPECT_NEAR(w[0].shear_stress, shear, 1e-12);
  EXPECT_NEAR(w[0].rolling_normal_stress, normal, 1e-12);
  EXPECT_NEAR(w[0].impulse_angle_deg, std::atan2(shear, normal) * 180.0 / M_PI, 1e-9);
  // The force runs from the floor to the centre, R = 1 inside strip 0 (2 thick, 20 wide):
  const auto s = rec.strips();
  EXPECT_NEAR(s[0].collisional[YY], std::cos(alpha) * 1.0 / (2.0 * width), 1e-12);
  EXPECT_NEAR(s[0].collisional[YX], -std::sin(alpha) * q / (1.0 + q) * 1.0 / (2.0 * width), 1e-12);
  EXPECT_EQ(s[1].collisional[YY], 0.0);
}

// ---------------------------------------------------------------------------------------------
// What the engine reports (engine_api/collision_observer.hpp), for collisions worked out by hand.

namespace {

struct Log : CollisionObserver {
  std::vector<PairCollision> pairs;
  std::vector<WallCollision> walls;
  void on_pair(const PairCollision& c) override { pairs.push_back(c); }
  void on_wall(const WallCollision& c) override { walls.push_back(c); }
};

void expect_near(const Vec3& a, const Vec3& b, double tolerance, const char* what) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << what << " component " << k;
}

}  // namespace

TEST(CollisionObserver, ReportsHeadOnAndWallCollisionsAsWorkedOut) {
  // Unit-mass discs of radius 1/2 (I = m R^2 / 2, so R^2 / I = 2). A and B meet head on at t = 1
  // (gap 2 closing at 2): elastic, J = 2 n on i, v_i - v_j = -2 n before. C (spin 2, velocity
  // (0.3, -1)) hits the rough floor (e_w = 0.8) at t = 0.5 at x = 8.15: its contact point slips at
  // v - R w x n = (1.3, 0); the floor stops that slip, J_t = -1.3 / (1 + 2), and reverses 0.8 of
  // the normal speed, J_n = 1.8.
  test::ParticleFile file("observed.csv",
                          "disc,3.0,5.0,0.0,1.0,0.0,0.0,0.0,0.0,0.0\n"
                          "disc,6.0,5.0,0.0,-1.0,0.0,0.0,0.0,0.0,0.0\n"
                          "disc,8.0,1.0,0.0,0.3,-1.0,0.0,0.0,0.0,2.0\n",
                          "species,x,y,z,vx,vy,vz,wx,wy,wz");
  const std::string text = walled_discs_case(10.0, 10.0, file.path(), 0.8, "rough");
  EdmdEngine<2> e = engine2(text);
  Log log;
  e.set_observer(&log);
  e.advance_to(1.2);
  ASSERT_EQ(log.pairs.size(), 1u);
  ASSERT_EQ(log.walls.size(), 1u);
  const PairCollision& p = log.pairs[0];
  EXPECT_NEAR(p.time, 1.0, 1e-12);
  expect_near(p.xi - p.xj, p.normal, 1e-12, "separation at contact");
  EXPECT_NEAR(std::fabs(p.normal.x), 1.0, 1e-12);
  expect_near(p.impulse, 2.0 * p.normal, 1e-12, "impulse");
  expect_near(p.relative_velocity_before, -2.0 * p.normal, 1e-12, "relative velocity");
  expect_near(p.contact, {4.5, 5.0, 0.0}, 1e-12, "contact point");
  EXPECT_NEAR(p.dissipated, 0.0, 1e-12);
  const WallCollision& w = log.walls[0];
  EXPECT_NEAR(w.time, 0.5, 1e-12);
  EXPECT_EQ(e.state().walls[w.wall].face, 2);  // ylo
  expect_near(w.x, {8.15, 0.5, 0.0}, 1e-12, "centre");
  expect_near(w.contact, {8.15, 0.0, 0.0}, 1e-12, "contact point");
  expect_near(w.slip_velocity_before, {1.3, 0.0, 0.0}, 1e-12, "slip");
  expect_near(w.impulse, {-1.3 / 3.0, 1.8, 0.0}, 1e-12, "impulse");
  // Energy lost: 1/2 (0.3^2 + 1) + 1/2 I 2^2 before, after from the impulses.
  const double inertia = 0.5 * 0.25;
  const double vx = 0.3 - 1.3 / 3.0, vy = 0.8, spin = 2.0 - 0.5 / inertia * (1.3 / 3.0);  // w' = w - (R/I) (n x J)_z
  const double lost =
      0.5 * (0.09 + 1.0) + 0.5 * inertia * 4.0 - (0.5 * (vx * vx + vy * vy) + 0.5 * inertia * spin * spin);
  EXPECT_NEAR(w.dissipated, lost, 1e-12);
  EXPECT_GT(w.dissipated, 0.0);
}
