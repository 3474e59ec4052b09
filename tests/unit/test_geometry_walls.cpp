// [[geometry]] walls in the soft-sphere engine: a tilted plane is the box face under tilted gravity
// (every contact law, to round-off), a sphere in a turning drum settles where friction balances
// gravity (rigid-body mechanics), the energy budget closes with turning and vibrating walls, and bad
// geometry is refused naming the key.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <variant>

#include "grainflow/core/error.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/run/case_loader.hpp"
#include "sphere_path.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

constexpr double kG = 9.81, kTheta = 0.35;  // rad, ~20 degrees
constexpr double kDiameter = 0.002;

using test::law_keys;
using test::Motion3;
using test::species_keys;
using test::wall_keys;

// One sphere released 0.3 d above the wall, moving down the slope and towards the wall with some
// spin: it bounces, slides and then rolls. `tilted_plane`: gravity vertical and the wall a plane
// turned by theta; else the ylo face with gravity turned by -theta. Returned in the face's frame.
std::vector<Motion3> run_sphere(std::string_view law, bool tilted_plane, int steps) {
  const double c = std::cos(kTheta), s = std::sin(kTheta);
  // The face frame's (x along the slope, y off the wall) to the plane's: a turn by -theta about z.
  auto to_plane = [&](const Vec3& a) { return Vec3{c * a.x + s * a.y, -s * a.x + c * a.y, a.z}; };
  auto to_face = [&](const Vec3& a) { return Vec3{c * a.x - s * a.y, s * a.x + c * a.y, a.z}; };
  Vec3 x{0.0, 1.3 * 0.5 * kDiameter, 0.01}, v{0.05, -0.1, 0.02}, w{0.0, 0.0, -20.0};
  if (tilted_plane) x = to_plane(x), v = to_plane(v), w = to_plane(w);
  else x.x += 0.01;
  std::ostringstream row, t;
  row.precision(17);
  row << "glass," << x.x << ',' << x.y << ',' << x.z << ',' << v.x << ',' << v.y << ',' << v.z << ',' << w.x << ','
      << w.y << ',' << w.z << '\n';
  const test::ParticleFile csv(tilted_plane ? "plane.csv" : "face.csv", row.str(),
                               "species,x,y,z,vx,vy,vz,wx,wy,wz");
  t.precision(17);
  t << "[domain]\n";
  if (tilted_plane) {
    t << "lo = [-0.02, -0.02, 0.0]\nhi = [0.02, 0.02, 0.02]\n"
      << "boundary = { x = \"open\", y = \"open\", z = \"periodic\" }\n"
      << "[gravity]\nvector = [0.0, " << -kG << ", 0.0]\n";
  } else {
    t << "lo = [0.0, 0.0, 0.0]\nhi = [0.02, 0.02, 0.02]\n"
      << "boundary = { x = \"periodic\", y = [\"wall\", \"open\"], z = \"periodic\" }\n"
      << "[gravity]\nvector = [" << kG * s << ", " << -kG * c << ", 0.0]\n";
  }
  t << "[[species]]\nname = \"glass\"\ndiameter = " << kDiameter << "\ndensity = 2500.0\n"
    << species_keys(law) << "[particles]\ninit = \"file\"\nfile = \"" << csv.path() << "\"\n[contact]\n"
    << law_keys(law);
  if (tilted_plane)
    t << "[[geometry]]\nname = \"slope\"\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [" << s << ", " << c
      << ", 0.0]\n";
  else
    t << "[walls.ylo]\n";
  t << wall_keys(law) << "[run]\nduration = 1.0\ntime_step = 2.0e-6\n";
  auto engine = test::engine_from_toml(t.str(), testing::TempDir() + "sphere.toml", 1);
  std::vector<Motion3> path;
  std::visit(
      [&](auto& e) {
        const auto& p = e.state().particles;
        const Vec3 start = tilted_plane ? Vec3{} : Vec3{0.01, 0.0, 0.0};
        for (int k = 0; k < steps; ++k) {
          e.step();
          if (k % 100 != 99) continue;
          const Vec3 at = e.unwrapped_position(0) - start;
          path.push_back(tilted_plane ? Motion3{to_face(at), to_face(p.velocity[0]), to_face(p.angular_velocity[0])}
                                      : Motion3{at, p.velocity[0], p.angular_velocity[0]});
        }
      },
      engine);
  return path;
}

// Over 0.04 s (20000 steps) the sphere bounces (contacts begin and end), slides and rolls ~1 cm. The
// two runs differ only in round-off: the plane's normal and the turned coordinates carry ~1e-16
// relative errors, which the contact's spring turns into force differences of the same relative
// size; summed over the steps they stay near 1e-13 m (measured below 1e-14 m). A wrong sign, axis or
// surface velocity would be off by the contact's physics, >= 1e-6 m. 1e-11 m and 1e-8 m/s (1e-5
// rad/s on the spin, of ~20 rad/s) lie decades from both.
TEST(GeometryWalls, TiltedPlaneMovesTheSphereAsTiltedGravityDoesForEveryLaw) {
  for_each_contact_law([&]<ContactLaw Law>() {
    const auto face = run_sphere(Law::name, false, 20000), plane = run_sphere(Law::name, true, 20000);
    ASSERT_EQ(face.size(), plane.size());
    const auto [dx, dv, dw] = test::largest_differences(face, plane);
    EXPECT_LT(dx, 1e-11) << Law::name;
    EXPECT_LT(dv, 1e-8) << Law::name;
    EXPECT_LT(dw, 1e-5) << Law::name;
    EXPECT_GT(face.back().x.x, 1e-3) << Law::name << ": the sphere should have travelled down the slope";
  });
}

// A sphere in a drum turning at w about its horizontal axis is carried up the rising side until the
// wall's friction F on it balances gravity's pull along the wall, F = m g sin(phi), with N = m g
// cos(phi) (its centre at rest: no centripetal term). If it rolls, the torque of F about its centre
// must balance the rolling resistance's couple mu_r r N (constant-torque model, R* = r against a
// wall): tan(phi) = mu_r. If mu_r exceeds mu it cannot spin up and slides: F = mu N, tan(phi) = mu.
// It starts at rest at the bottom, pressed in by its weight. Neither the rolling couple nor the
// sliding friction changes sign as it swings about the equilibrium (the wall always moves faster
// than the sphere's contact point), so nothing damps the swing: a pendulum of period
// 2 pi sqrt(1.4 (R - r) / g) ~ 0.2 s whose mean is the equilibrium. The angle is averaged over 10 s
// after 1 s of start.
double settled_angle(double mu, double mu_r) {
  const std::string row = "glass,0.0,-0.00898997,0.01,0,0,0\n";  // 9 mm - m g / kn below the axis
  const test::ParticleFile csv("drum.csv", row);
  std::ostringstream t;
  t << "[domain]\nlo = [-0.011, -0.011, 0.0]\nhi = [0.011, 0.011, 0.02]\n"
    << "boundary = { x = \"open\", y = \"open\", z = \"periodic\" }\n"
    << "[gravity]\nvector = [0.0, -9.81, 0.0]\n"
    << "[[species]]\nname = \"glass\"\ndiameter = 0.002\ndensity = 2500.0\n"
    << "[particles]\ninit = \"file\"\nfile = \"" << csv.path() << "\"\n"
    << "[contact]\nmodel = \"linear_dashpot\"\nkn = 1.0e4\ngamma_n = 0.05\nfriction = " << mu
    << "\nrolling_model = \"constant_torque\"\nrolling_friction = " << mu_r << "\n"
    << "[[geometry]]\nname = \"drum\"\ntype = \"cylinder\"\npoint = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\n"
    << "radius = 0.01\nfriction = " << mu << "\n"
    << "[geometry.motion]\nangular_velocity = [0.0, 0.0, 2.0]\n"
    << "[run]\nduration = 1.0\ntime_step = 2.0e-6\n";
  auto engine = test::engine_from_toml(t.str(), testing::TempDir() + "drum.toml", 1);
  return std::visit(
      [&](auto& e) {
        for (int k = 0; k < 500000; ++k) e.step();
        double sum = 0.0;
        const int samples = 5000000;
        for (int k = 0; k < samples; ++k) {
          e.step();
          const Vec3 x = e.state().particles.position[0];
          sum += std::atan2(x.x, -x.y);  // from the bottom, towards the rising (+x) side
        }
        return sum / samples;
      },
      engine);
}

// The mean over ~45 swings of amplitude <= 0.2 rad is the equilibrium to within 0.2 / (pi 45) ~ 1.5e-3
// rad, hence 3e-3; a wall taken as still would leave the sphere at the bottom (0 against 0.1 and 0.2).
TEST(GeometryWalls, SphereInATurningDrumSettlesWhereFrictionBalancesGravity) {
  EXPECT_NEAR(settled_angle(0.5, 0.1), std::atan(0.1), 3e-3);  // rolls: the rolling couple limits it
  EXPECT_NEAR(settled_angle(0.2, 0.5), std::atan(0.2), 3e-3);  // slides: Coulomb friction limits it
}

}  // namespace

namespace {

// A small drum: 150 frictional spheres in a turning cylinder, plus a tilted, vibrating plane cutting
// across its bottom (driven by [drive]), so that both a turning wall's w x r and a translating
// wall's work enter the budget.
std::string drum_bed(const std::string& extra = "") {
  return R"([domain]
lo = [-0.021, -0.021, 0.0]
hi = [0.021, 0.021, 0.006]
boundary = { x = "open", y = "open", z = "periodic" }
[gravity]
vector = [0.0, -9.81, 0.0]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
count = 150
[particles]
init = "random"
region_lo = [-0.02, -0.02, 0.0]
region_hi = [0.02, 0.0, 0.006]
seed = 4
[contact]
model = "linear_dashpot"
kn = 1.0e4
gamma_n = 0.05
friction = 0.4
[[geometry]]
name = "drum"
type = "cylinder"
point = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]
radius = 0.02
[geometry.motion]
angular_velocity = [0.0, 0.0, 6.0]
[[geometry]]
name = "floor"
type = "plane"
point = [0.0, -0.016, 0.0]
normal = [0.2, 1.0, 0.0]
[geometry.motion]
drive = true
[drive]
amplitude = [0.0, 0.0005, 0.0]
frequency = [0.0, 30.0, 0.0]
start = 0.05
ramp = 0.05
[run]
duration = 0.3
time_step = 1.0e-5
)" + extra;
}

// The budget's residual is the integrator's (velocity Verlet against the trapezoidal rule for the
// forces' work), of order (dt / t_c)^2 ~ 1e-3 of the dissipation per collision and averaging out;
// the flat-walled beds of test_dem_energy_budget close to ~1e-5. A turning wall's work booked at the
// wall's translation alone (w x r left out) leaves a residual of the order of its whole input.
TEST(GeometryWalls, EnergyBudgetClosesWithTurningAndVibratingWalls) {
  const CaseConfig c = load_case_from_string(drum_bed(), "drum_bed.toml");
  auto engine = test::engine_for(c, 2);
  const auto b = std::visit(
      [&](auto& e) {
        const long steps = std::lround(c.run.duration / e.state().time_step);
        for (long k = 0; k < steps; ++k) e.step();
        return e.energy_budget();
      },
      engine);
  EXPECT_GT(b.wall_work, 0.0);
  EXPECT_GT(b.dissipated, 0.0);
  RecordProperty("residual", std::to_string(b.residual(1.0)));
  EXPECT_LT(std::fabs(b.residual(1.0)), 1e-3);
}

// Bad geometry is refused before anything runs, naming the table's key and the reason.
void expect_refused(const std::string& text, const std::string& key, const std::string& reason) {
  try {
    load_case_from_string(text, "bad.toml");
    ADD_FAILURE() << "accepted; expected a refusal of " << key;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(key), std::string::npos) << what;
    EXPECT_NE(what.find(reason), std::string::npos) << what;
  }
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(GeometryWalls, BadGeometryIsRefusedNamingTheKey) {
  const std::string bed = drum_bed();
  expect_refused(replaced(bed, "axis = [0.0, 0.0, 1.0]", "axis = [0.0, 0.0, 0.0]"), "geometry.0.axis", "zero vector");
  expect_refused(replaced(bed, "radius = 0.02", "radius = -0.02"), "geometry.0.radius", "geometry 'drum' (cylinder)");
  expect_refused(replaced(bed, "type = \"cylinder\"", "type = \"torus\""), "geometry.0.type",
                 "registered: plane, cylinder, cone");
  expect_refused(replaced(bed, "name = \"floor\"", "name = \"drum\""), "geometry.1.name", "names two geometries");
  const std::string cone = replaced(bed, "type = \"cylinder\"\npoint = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nradius = 0.02",
                                    "type = \"cone\"\npoint = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nlength = 0.006\n"
                                    "radius_start = 0.0\nradius_end = 0.0");
  expect_refused(cone, "geometry.0.radius_end", "both are 0");
  expect_refused(replaced(bed, "[drive]", "[drive0]"), "geometry.1.motion.drive", "[drive]");
  // Discs: a plane whose normal leaves the x-y plane would push them off it.
  try {
    load_case_from_string(replaced(bed, "normal = [0.2, 1.0, 0.0]", "normal = [0.2, 1.0, 0.3]"), "discs.toml",
                          {"engine.dimension=2"});
    ADD_FAILURE() << "a plane tilted out of the discs' plane was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("geometry.1.normal"), std::string::npos) << e.what();
  }
  // A particle placed behind the drum's wall.
  const test::ParticleFile csv("outside.csv", "glass,0.0,-0.0205,0.003,0,0,0\n");
  std::string placed = replaced(bed, "init = \"random\"", "init = \"file\"\nfile = \"" + csv.path() + "\"");
  placed = replaced(placed, "count = 150\n", "");
  try {
    const CaseConfig c = load_case_from_string(placed, "placed.toml");
    dem::build_dem_state(c);
    ADD_FAILURE() << "a particle inside the drum's wall was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("inside the wall 'drum'"), std::string::npos) << e.what();
  }
  // The event-driven engine keeps its box faces.
  expect_refused(
      "[engine]\nkind = \"edmd\"\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [1.0, 1.0, 1.0]\nboundary = { x = \"wall\", y = \"wall\", z = \"wall\" }\n"
      "[[species]]\nname = \"a\"\ndiameter = 0.1\ndensity = 1.0\ncount = 10\n"
      "[[geometry]]\nname = \"drum\"\ntype = \"cylinder\"\npoint = [0.5, 0.5, 0.0]\naxis = [0.0, 0.0, 1.0]\nradius = 0.4\n",
      "geometry", "event-driven engine keeps its box faces");
}

}  // namespace
