// Case files: a valid minimal case loads, and every invalid case is refused with an InputError that
// names the file, the key and the reason (INTERFACE.md: exit status 2, nothing written). Also the
// --set overrides and the geometric checks of section 2.6.3 (bumpy walls must hold the particles).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/dem/dem_state.hpp"
#include "grainflow/dem/derived_quantities.hpp"

using namespace grainflow;

namespace {

const std::string kLabel = "cases/test/minimal.toml";

// 20 glass spheres (d = 3 mm) in a 6.7 d x 16.7 d x 6.7 d box: solids fraction 0.014, far from any
// limit, so each test below breaks exactly one thing.
const std::string kMinimal = R"([engine]
kind = "dem"
dimension = 3

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.05, 0.02]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[gravity]
vector = [0.0, -9.81, 0.0]

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 20

[particles]
init = "random"
seed = 3

[contact]
model = "walton_braun"
k1 = 1.0e6
restitution = 0.9
friction = 0.5

[walls.ylo]
restitution = 0.8
friction = 0.3

[run]
duration = 0.01

[output]
interval = 0.001
)";

// Replaces the one occurrence of `from` in `text` (the test fails if there is none).
std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the case text";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// Loads `text` and requires an InputError naming `key` (exactly), with `reason_part` in its reason,
// and the file label in its message.
void expect_input_error(const std::string& text, const std::string& key, const std::string& reason_part,
                        const std::vector<std::string>& overrides = {}, const std::string& file_part = kLabel) {
  try {
    load_case_from_string(text, kLabel, overrides);
    ADD_FAILURE() << "expected InputError for key '" << key << "' (" << reason_part << "), but the case loaded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.key(), key) << what;
    EXPECT_NE(e.file().find(file_part), std::string::npos) << what;
    EXPECT_NE(e.reason().find(reason_part), std::string::npos)
        << "reason '" << e.reason() << "' lacks '" << reason_part << "'";
    // The message a user sees carries all three.
    EXPECT_NE(what.find(kLabel), std::string::npos) << what;
    EXPECT_NE(what.find(key), std::string::npos) << what;
    EXPECT_NE(what.find(e.reason()), std::string::npos) << what;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError for key '" << key << "', got another exception: " << e.what();
  }
}

}  // namespace

TEST(CaseLoader, MinimalCaseLoadsWithItsValuesAndDefaults) {
  const CaseConfig c = load_case_from_string(kMinimal, kLabel);
  EXPECT_EQ(c.path, kLabel);
  EXPECT_EQ(c.engine.kind, "dem");
  EXPECT_EQ(c.domain.hi, (Vec3{0.02, 0.05, 0.02}));
  EXPECT_TRUE(c.domain.periodic(0));
  EXPECT_FALSE(c.domain.periodic(1));
  EXPECT_TRUE(c.domain.periodic(2));
  EXPECT_EQ(c.domain.faces[2], FaceKind::wall);
  EXPECT_EQ(c.domain.faces[3], FaceKind::open);
  ASSERT_EQ(c.species.size(), 1u);
  EXPECT_EQ(c.species[0].name, "glass");
  EXPECT_DOUBLE_EQ(c.species[0].diameter, 0.003);
  EXPECT_EQ(c.species[0].count, 20);
  EXPECT_DOUBLE_EQ(c.contact.parameters.at("k1"), 1.0e6);
  EXPECT_DOUBLE_EQ(c.contact.parameters.at("restitution"), 0.9);
  EXPECT_DOUBLE_EQ(c.contact.friction, 0.5);
  EXPECT_DOUBLE_EQ(c.walls[2].contact.at("restitution"), 0.8);
  EXPECT_DOUBLE_EQ(c.walls[2].friction, 0.3);
  EXPECT_EQ(c.particles.seed, 3u);
  EXPECT_FALSE(c.drive.enabled);
  EXPECT_DOUBLE_EQ(c.run.duration, 0.01);
  EXPECT_DOUBLE_EQ(c.run.time_step, 0.0);  // default: eq. (2-5-4)
  EXPECT_EQ(c.run.collision_steps, 15);    // default n
}

TEST(CaseLoader, UnknownKeysAreErrorsAtEveryLevel) {
  expect_input_error(kMinimal + "\n[solver]\nkind = \"x\"\n", "solver", "unknown key");
  expect_input_error(replace(kMinimal, "k1 = 1.0e6", "k1 = 1.0e6\nk11 = 2.0e6"), "contact.k11", "unknown key");
  expect_input_error(replace(kMinimal, "friction = 0.3", "friction = 0.3\nrestitutio = 0.5"), "walls.ylo.restitutio",
                     "unknown key");
  expect_input_error(replace(kMinimal, "count = 20", "count = 20\ncolour = \"red\""), "species.0.colour",
                     "unknown key");
  expect_input_error(replace(kMinimal, "z = \"periodic\" }", "z = \"periodic\", w = \"wall\" }"), "domain.boundary.w",
                     "unknown key");
}

TEST(CaseLoader, WrongTypesAreErrors) {
  expect_input_error(replace(kMinimal, "diameter = 0.003", "diameter = \"0.003\""), "species.0.diameter",
                     "expected a number");
  expect_input_error(replace(kMinimal, "count = 20", "count = 20.5"), "species.0.count", "expected an integer");
  expect_input_error(replace(kMinimal, "hi = [0.02, 0.05, 0.02]", "hi = [0.02, 0.05]"), "domain.hi", "3 numbers");
  expect_input_error(replace(kMinimal, "kind = \"dem\"", "kind = 1"), "engine.kind", "expected a string");
  expect_input_error(replace(kMinimal, "[walls.ylo]", "[walls.ylo]\nvelocity = [0.0, \"a\", 0.0]"),
                     "walls.ylo.velocity", "3 numbers");
}

TEST(CaseLoader, MissingRequiredKeysAreErrors) {
  expect_input_error(replace(kMinimal, "k1 = 1.0e6", ""), "contact.k1", "is required");
  expect_input_error(replace(kMinimal, "duration = 0.01", ""), "run.duration", "is required");
  expect_input_error(replace(kMinimal, "hi = [0.02, 0.05, 0.02]", ""), "domain.hi", "is required");
  expect_input_error(replace(kMinimal, "diameter = 0.003", ""), "species.0.diameter", "is required");
  expect_input_error(replace(kMinimal, "name = \"glass\"", ""), "species.0.name", "is required");
}

TEST(CaseLoader, RestitutionMustLieInZeroToOne) {
  for (const char* bad : {"0.0", "-0.1", "1.5"}) {
    expect_input_error(replace(kMinimal, "restitution = 0.9", std::string("restitution = ") + bad),
                       "contact.restitution", "(0, 1]");
    expect_input_error(replace(kMinimal, "restitution = 0.8", std::string("restitution = ") + bad),
                       "walls.ylo.restitution", "(0, 1]");
  }
  // The closed end: e = 1 (elastic) is valid.
  EXPECT_NO_THROW(load_case_from_string(replace(kMinimal, "restitution = 0.9", "restitution = 1.0"), kLabel));
}

TEST(CaseLoader, RollingResistanceKeysAreChecked) {
  const std::string with = replace(kMinimal, "friction = 0.5\n", "friction = 0.5\nrolling_friction = 0.1\n");
  const CaseConfig c = load_case_from_string(with, kLabel);
  EXPECT_EQ(c.contact.rolling_model, "epsd");  // the default model once mu_r is given
  EXPECT_EQ(c.contact.rolling_damping, 0.3);
  EXPECT_EQ(c.contact.rolling_stiffness, 2.25);
  EXPECT_EQ(load_case_from_string(kMinimal, kLabel).contact.rolling_model, "none");
  for (const char* bad : {"-0.1", "1.5"})
    expect_input_error(
        replace(kMinimal, "friction = 0.5\n", std::string("friction = 0.5\nrolling_friction = ") + bad + "\n"),
        "contact.rolling_friction", "[0, 1]");
  expect_input_error(replace(kMinimal, "friction = 0.5\n", "friction = 0.5\nrolling_model = \"epsd\"\n"),
                     "contact.rolling_model", "needs rolling_friction");
  // mu_r = 0 switches a model off (an override of a case with rolling resistance).
  EXPECT_EQ(load_case_from_string(with, kLabel, {"contact.rolling_friction=0"}).contact.rolling_model, "none");
  expect_input_error(replace(with, "rolling_friction = 0.1\n", "rolling_friction = 0.1\nrolling_model = \"cdt\"\n"),
                     "contact.rolling_model", "unknown rolling model 'cdt' (registered: none, constant_torque, epsd)");
  expect_input_error(replace(with, "rolling_friction = 0.1\n",
                             "rolling_friction = 0.1\nrolling_model = \"constant_torque\"\nrolling_damping = 0.2\n"),
                     "contact.rolling_damping", "epsd");
  expect_input_error(replace(with, "rolling_friction = 0.1\n", "rolling_friction = 0.1\nrolling_damping = 1.5\n"),
                     "contact.rolling_damping", "[0, 1]");
  expect_input_error(replace(with, "rolling_friction = 0.1\n", "rolling_friction = 0.1\nrolling_stiffness = 0.0\n"),
                     "contact.rolling_stiffness", "positive");
  // A wall's own mu_r, only where the particles have a model.
  EXPECT_EQ(load_case_from_string(replace(with, "friction = 0.3\n", "friction = 0.3\nrolling_friction = 0.2\n"), kLabel)
                .walls[2]
                .rolling_friction,
            0.2);
  expect_input_error(replace(kMinimal, "friction = 0.3\n", "friction = 0.3\nrolling_friction = 0.2\n"),
                     "walls.ylo.rolling_friction", "contact.rolling_friction");
}

TEST(CaseLoader, NonPositiveMaterialPropertiesAreErrors) {
  for (const char* bad : {"0.0", "-0.003"}) {
    expect_input_error(replace(kMinimal, "diameter = 0.003", std::string("diameter = ") + bad), "species.0.diameter",
                       "must be positive");
    expect_input_error(replace(kMinimal, "density = 2490.0", std::string("density = ") + bad), "species.0.density",
                       "must be positive");
    expect_input_error(replace(kMinimal, "k1 = 1.0e6", std::string("k1 = ") + bad), "contact.k1", "must be positive");
  }
  expect_input_error(replace(kMinimal, "count = 20", "count = -1"), "species.0.count", "negative");
}

TEST(CaseLoader, ParticlesThatCannotFitAreErrors) {
  // Random placement: 1200 spheres of 1.41e-8 m^3 in 2e-5 m^3 is a solids fraction of 0.85.
  expect_input_error(replace(kMinimal, "count = 20", "count = 1200"), "species.count", "placement region");
  // The same in a small placement region: 20 spheres in 6e-3 x 6e-3 x 6e-3 m^3 fill 1.31.
  expect_input_error(
      replace(kMinimal, "seed = 3", "seed = 3\nregion_lo = [0.0, 0.0, 0.0]\nregion_hi = [0.006, 0.006, 0.006]"),
      "species.count", "placement region");
  // Lattice: floor(0.02 / 0.00306)^2 floor(0.05 / 0.00306) = 6 x 6 x 16 = 576 sites; 577 do not fit.
  const std::string lattice = replace(kMinimal, "init = \"random\"", "init = \"lattice\"");
  EXPECT_NO_THROW(load_case_from_string(replace(lattice, "count = 20", "count = 576"), kLabel));
  expect_input_error(replace(lattice, "count = 20", "count = 577"), "species.count", "lattice sites");
  // A placement region reaching outside the box.
  expect_input_error(
      replace(kMinimal, "seed = 3", "seed = 3\nregion_lo = [0.0, -0.01, 0.0]\nregion_hi = [0.02, 0.03, 0.02]"),
      "particles.region_lo", "inside the domain");
}

TEST(CaseLoader, TimeStepTooLargeForTheContactIsAnError) {
  // Binary Walton-Braun contact of two spheres (reduced mass m/2): loading quarter period on K1 plus
  // unloading on K2 = K1/e^2, t_c = (pi/2) sqrt(m / (2 K1)) (1 + e) (eqs. 2-5-2, 2-5-3).
  const double m = M_PI / 6.0 * 0.003 * 0.003 * 0.003 * 2490.0;
  const double contact = 0.5 * M_PI * std::sqrt(m / (2.0 * 1.0e6)) * 1.9;
  // The validation asks for at least 5 steps per contact (stable and accurate velocity Verlet).
  auto with_step = [&](double dt) {
    char text[64];
    std::snprintf(text, sizeof text, "duration = 0.01\ntime_step = %.9e", dt);
    return replace(kMinimal, "duration = 0.01", text);
  };
  EXPECT_NO_THROW(load_case_from_string(with_step(contact / 5.1), kLabel));
  expect_input_error(with_step(contact / 4.9), "run.time_step", "steps");
  expect_input_error(with_step(1.0e-3), "run.time_step", "steps");
  // Through n of eq. (2-5-4): dt = 2 t_r / n gives n (1 + e) / (2 e) steps per contact, so n = 5
  // gives 5.28 (valid) and n = 4 gives 4.22 (refused).
  EXPECT_NO_THROW(
      load_case_from_string(replace(kMinimal, "duration = 0.01", "duration = 0.01\ncollision_steps = 5"), kLabel));
  expect_input_error(replace(kMinimal, "duration = 0.01", "duration = 0.01\ncollision_steps = 4"),
                     "run.collision_steps", "steps");
}

TEST(CaseLoader, DriveOnAPeriodicOrOpenFaceIsAnError) {
  const std::string drive = "\n[drive]\nface = \"%s\"\namplitude = [0.0, 0.001, 0.0]\nfrequency = [0.0, 20.0, 0.0]\n";
  auto with_face = [&](const char* face) {
    char text[256];
    std::snprintf(text, sizeof text, drive.c_str(), face);
    return kMinimal + text;
  };
  EXPECT_NO_THROW(load_case_from_string(with_face("ylo"), kLabel));
  expect_input_error(with_face("xlo"), "drive.face", "periodic");
  expect_input_error(with_face("zhi"), "drive.face", "periodic");
  expect_input_error(with_face("yhi"), "drive.face", "open");
  expect_input_error(with_face("floor"), "drive.face", "unknown face");
}

namespace {

// The minimal case with a bumpy floor (bumps of the species' diameter, 3 mm) of the given lattice
// and nominal spacing.
std::string bumpy_case(const std::string& lattice, double spacing) {
  char keys[128];
  std::snprintf(keys, sizeof keys, "friction = 0.3\nlattice = \"%s\"\nspacing = %.6g", lattice.c_str(), spacing);
  return replace(replace(kMinimal, "y = [\"wall\", \"open\"]", "y = [\"bumpy\", \"open\"]"), "friction = 0.3", keys);
}

struct BumpGeometry {
  double largest_hole = 0.0;     // m, largest distance from a point of the plane to its nearest bump centre
  double closest_bumps = 1e300;  // m, smallest centre distance between two bumps
  std::size_t bumps = 0;
};

// Measures the bumps of the floor of a built state in the periodic x-z plane of side L. The largest
// hole comes from a grid of `grid`^2 points: it underestimates by at most half a grid diagonal.
BumpGeometry measure_bumps(const dem::DemState& s, double L, int grid) {
  std::vector<Vec3> bumps;
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    if (s.particles.motion[i] == Motion::wall_bump) bumps.push_back(s.particles.position[i]);
  BumpGeometry g;
  g.bumps = bumps.size();
  auto distance = [L](double x0, double z0, double x1, double z1) {
    double dx = std::fabs(x0 - x1), dz = std::fabs(z0 - z1);
    dx = std::min(dx, L - dx);
    dz = std::min(dz, L - dz);
    return std::hypot(dx, dz);
  };
  for (std::size_t i = 0; i < bumps.size(); ++i)
    for (std::size_t j = i + 1; j < bumps.size(); ++j)
      g.closest_bumps = std::min(g.closest_bumps, distance(bumps[i].x, bumps[i].z, bumps[j].x, bumps[j].z));
  for (int a = 0; a < grid; ++a)
    for (int b = 0; b < grid; ++b) {
      const double x = (a + 0.5) * L / grid, z = (b + 0.5) * L / grid;
      double nearest = 1e300;
      for (const Vec3& bump : bumps) nearest = std::min(nearest, distance(x, z, bump.x, bump.z));
      g.largest_hole = std::max(g.largest_hole, nearest);
    }
  return g;
}

}  // namespace

TEST(CaseLoader, BumpyWallSpacingThatLetsParticlesThroughIsAnError) {
  // Section 2.6.3: a free sphere of radius r passes between bumps of radius R where the plane has a
  // point R + r or farther from every bump centre; on a square lattice of spacing s that point lies
  // s/sqrt(2) from its four bumps, so with d = bump = 3 mm spacings above sqrt(2) 3 mm = 4.24 mm
  // leak (triangular: s/sqrt(3), above 5.20 mm). The lattice may be stretched to tile the 20 mm
  // face; these spacings are far enough from the limits for any stretching to keep the verdict.
  EXPECT_NO_THROW(load_case_from_string(bumpy_case("square", 0.004), kLabel));  // 5 x 5 bumps, hole 2.83 mm
  expect_input_error(bumpy_case("square", 0.006), "walls.ylo.spacing", "through");
  expect_input_error(bumpy_case("triangular", 0.0067), "walls.ylo.spacing", "through");
  // Bumps closer than their diameter would overlap.
  expect_input_error(bumpy_case("square", 0.0029), "walls.ylo.spacing", "overlap");
}

// For every spacing, the verdict of the validation must match the bumps as they are built: refused
// ("through") exactly when some point of the floor plane, also across the periodic seam, lies
// R + r or farther from every bump centre, refused ("overlap") exactly when two bumps are closer
// than their diameter, accepted otherwise. The geometry is measured on the built state (the
// placement is built from an accepted base case with the spacing changed, which skips validation).
// The 0.1 mm grid underestimates a hole by at most 0.071 mm: verdicts within that of the limit are
// not judged.
TEST(CaseLoader, BumpyWallVerdictMatchesTheBuiltGeometry) {
  const double L = 0.02, reach = 0.0015 + 0.0015, diameter = 0.003;
  const int grid = 200;
  const double grid_error = 0.5 * std::sqrt(2.0) * L / grid;
  int accepted = 0, refused = 0, judged = 0;
  for (const char* lattice : {"square", "triangular"}) {
    CaseConfig base = load_case_from_string(bumpy_case(lattice, 0.004), kLabel);
    for (int k = 0; k <= 50; ++k) {
      const double spacing = 0.0028 + k * 0.0001;
      std::string verdict = "accepted";
      try {
        load_case_from_string(bumpy_case(lattice, spacing), kLabel);
        ++accepted;
      } catch (const InputError& e) {
        ++refused;
        EXPECT_EQ(e.key(), "walls.ylo.spacing") << lattice << " s = " << spacing << ": " << e.what();
        verdict = e.reason().find("overlap") != std::string::npos   ? "overlap"
                  : e.reason().find("through") != std::string::npos ? "through"
                                                                    : e.reason();
      }
      CaseConfig c = base;
      c.walls[2].spacing = spacing;
      const BumpGeometry g = measure_bumps(dem::build_dem_state(c), L, grid);
      const bool overlapping = g.closest_bumps < diameter * (1.0 - 1e-9);
      const std::string where = std::string(lattice) + " s = " + std::to_string(spacing) + " (" +
                                std::to_string(g.bumps) + " bumps, largest hole " + std::to_string(g.largest_hole) +
                                " m, closest bumps " + std::to_string(g.closest_bumps) + " m): " + verdict;
      if (overlapping) {
        EXPECT_EQ(verdict, "overlap") << where;
        continue;
      }
      if (std::fabs(g.largest_hole - reach) < grid_error) continue;  // too close to the limit to judge
      ++judged;
      if (g.largest_hole >= reach) EXPECT_EQ(verdict, "through") << where << "; a 3 mm sphere falls through";
      else EXPECT_EQ(verdict, "accepted") << where << "; no 3 mm sphere passes";
    }
  }
  EXPECT_GT(accepted, 5);
  EXPECT_GT(refused, 5);
  EXPECT_GT(judged, 80);
}

TEST(CaseLoader, SetOverridesChangeValues) {
  const CaseConfig c =
      load_case_from_string(kMinimal, kLabel,
                            {"species.0.count=7", "run.collision_steps=20", "domain.boundary.y=[\"wall\", \"wall\"]",
                             "particles.seed=11", "contact.friction=0.25", "species.0.frozen=false"});
  EXPECT_EQ(c.species[0].count, 7);  // numeric path segments index arrays of tables
  EXPECT_EQ(c.run.collision_steps, 20);
  EXPECT_EQ(c.domain.faces[3], FaceKind::wall);
  EXPECT_EQ(c.particles.seed, 11u);
  EXPECT_DOUBLE_EQ(c.contact.friction, 0.25);
  EXPECT_DOUBLE_EQ(c.contact.parameters.at("k1"), 1.0e6);  // untouched keys keep the file's values

  const CaseConfig k = load_case_from_string(kMinimal, kLabel, {"contact.k1=2e6"});
  EXPECT_DOUBLE_EQ(k.contact.parameters.at("k1"), 2e6);
  // A table that the file does not have is created by --set (here a whole drive).
  const CaseConfig d = load_case_from_string(
      kMinimal, kLabel, {"drive.amplitude=[0, 0.001, 0]", "drive.frequency=[0, 30, 0]", "drive.start=0.5"});
  EXPECT_TRUE(d.drive.enabled);
  EXPECT_DOUBLE_EQ(d.drive.start, 0.5);
  EXPECT_DOUBLE_EQ(d.drive.frequency.y, 30.0);
}

TEST(CaseLoader, BadSetOverridesAreErrorsMentioningSet) {
  expect_input_error(kMinimal, "contact.k11", "unknown key", {"contact.k11=2e6"}, "(--set)");
  expect_input_error(kMinimal, "contact.k1", "must be positive", {"contact.k1=-5"}, "(--set)");
  expect_input_error(kMinimal, "contact.k1", "expected a number", {"contact.k1=stiff"}, "(--set)");
  for (const char* bad : {"species.3.count=1", "nonsense", "contact..k1=3"}) {
    try {
      load_case_from_string(kMinimal, kLabel, {bad});
      ADD_FAILURE() << "--set " << bad << " was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("--set"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(kLabel), std::string::npos) << e.what();
    }
  }
}

TEST(CaseLoader, TomlSyntaxErrorReportsTheLine) {
  // Break the line "k1 = 1.0e6" and expect its line number in the message.
  const std::string broken = replace(kMinimal, "k1 = 1.0e6", "k1 = = 1.0e6");
  int line = 1;
  for (char ch : broken.substr(0, broken.find("k1 = ="))) line += ch == '\n';
  try {
    load_case_from_string(broken, kLabel);
    ADD_FAILURE() << "a TOML syntax error was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(kLabel), std::string::npos) << what;
    EXPECT_NE(what.find("line " + std::to_string(line)), std::string::npos)
        << what << " (expected line " << line << ")";
  }
}

TEST(CaseLoader, MissingFileIsAnInputError) {
  try {
    load_case("/nonexistent/dir/case.toml");
    ADD_FAILURE() << "a missing case file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/case.toml"), std::string::npos) << e.what();
  }
}

// An event-driven fcc lattice of 10 unit spheres in a periodic box with the given upper corner.
std::string sphere_lattice_case(const std::string& hi) {
  return R"([engine]
kind = "edmd"
dimension = 3
[domain]
lo = [0.0, 0.0, 0.0]
hi = )" + hi +
         R"(
boundary = { x = "periodic", y = "periodic", z = "periodic" }
[[species]]
name = "sphere"
diameter = 1.0
density = 1.9
count = 10
[particles]
init = "lattice"
lattice = "fcc"
[collision]
restitution = 1.0
[run]
duration = 1.0
[output]
interval = 0.5
)";
}

TEST(CaseLoader, CoarseGrainKeysAreChecked) {
  const std::string with = kMinimal + "\n[coarse_grain]\n";
  const CaseConfig c = load_case_from_string(with, kLabel);
  EXPECT_TRUE(c.coarse_grain.enabled);
  // Defaults from the diameter, whatever the units: a Gaussian of half a diameter, cells of one width.
  EXPECT_DOUBLE_EQ(c.coarse_grain.kernel_size(0.003), 0.0015);
  EXPECT_EQ(c.coarse_grain.grid({0.02, 0.05, 0.02}, 0.003, 3), (std::array<int, 3>{14, 34, 14}));
  expect_input_error(with + "kernel = \"box\"\n", "coarse_grain.kernel", "must be");
  expect_input_error(with + "cutoff = 0.004\n", "coarse_grain.cutoff", "belongs to kernel = \"lucy\"");
  expect_input_error(with + "kernel = \"lucy\"\nwidth = 0.004\n", "coarse_grain.width",
                     "belongs to kernel = \"gaussian\"");
  expect_input_error(with + "width = -1.0\n", "coarse_grain.width", "positive");
  expect_input_error(with + "cells = [4, 4]\n", "coarse_grain.cells", "three cell counts");
  expect_input_error(with + "cells = [4, 0, 4]\n", "coarse_grain.cells", "[1, 100000]");
  // 5 mm cells under a kernel of 1.5 mm standard deviation would bin, not coarse-grain.
  expect_input_error(with + "cells = [4, 10, 4]\n", "coarse_grain.cells", "not resolved");
  expect_input_error(with + "interval = 1.0e-9\n", "coarse_grain.interval", "shorter than one time step");
  expect_input_error(replace(sphere_lattice_case("[3.0, 3.0, 3.0]"), "[run]", "[coarse_grain]\n[run]"), "coarse_grain",
                     "DEM engine only");
}

// Found by fuzzing (make fuzz): a lattice placement over a huge region counted its sites in a long,
// and 1e8 x 1e8 x 1e8 sites overflowed it (undefined behaviour, caught by UBSan in the debug
// build). Sites are now counted in double: such a region validates, for both engines.
TEST(CaseLoader, HugeLatticeRegionCountsItsSitesWithoutOverflow) {
  EXPECT_NO_THROW(load_case_from_string(sphere_lattice_case("[1.0e8, 1.0e8, 1.0e8]"), kLabel));
  // The soft-sphere engine's check: 3 mm spheres on a lattice in a 300 km cube (1e8 diameters).
  const std::string dem = replace(replace(kMinimal, "init = \"random\"", "init = \"lattice\""),
                                  "hi = [0.02, 0.05, 0.02]", "hi = [3.0e5, 3.0e5, 3.0e5]");
  EXPECT_NO_THROW(load_case_from_string(dem, kLabel));
}

// Beyond 1e9 diameters along an axis positions cannot resolve a contact: refused, naming domain.hi.
TEST(CaseLoader, DomainBeyondPositionPrecisionIsRefused) {
  expect_input_error(sphere_lattice_case("[33.0, 33.0, 3.3e97]"), "domain.hi", "at most 1e9");
}

// Discs in the DEM engine: the plane must stay the plane of motion, so anything that would push a
// disc along z is refused, naming the key; the rest of a 3D case carries over.
TEST(CaseLoader, DemDiscsRefuseWhatWouldLeaveThePlane) {
  const std::string discs = replace(kMinimal, "dimension = 3", "dimension = 2");
  const CaseConfig c = load_case_from_string(discs, kLabel);
  EXPECT_EQ(c.engine.dimension, 2);
  // A disc of 3 mm at 2490 kg/m^2: its mass is density x area.
  EXPECT_DOUBLE_EQ(c.species[0].mass(2), 2490.0 * M_PI * 0.0015 * 0.0015);
  expect_input_error(replace(discs, "z = \"periodic\"", "z = \"wall\""), "domain.boundary", "no walls along z");
  expect_input_error(replace(discs, "[0.0, -9.81, 0.0]", "[0.0, -9.81, 1.0]"), "gravity.vector",
                     "z component must be 0");
  expect_input_error(replace(discs, "[walls.ylo]", "[walls.ylo]\nvelocity = [0.0, 0.0, 0.1]"), "walls.ylo.velocity",
                     "z component must be 0");
  expect_input_error(replace(replace(discs, "y = [\"wall\", \"open\"]", "y = [\"bumpy\", \"open\"]"), "[walls.ylo]",
                             "[walls.ylo]\nlattice = \"triangular\""),
                     "walls.ylo.lattice", "one row of half-discs");
  expect_input_error(discs + "\n[coarse_grain]\ncells = [10, 20, 4]\n", "coarse_grain.cells", "one cell along z");
  // A 2D grid defaults to one cell along z, and Lucy's 2D spread sets the default cell count.
  EXPECT_EQ(c.coarse_grain.grid({0.02, 0.05, 0.02}, 0.003, 2)[2], 1);
  EXPECT_DOUBLE_EQ(lucy_standard_deviation(1.0, 2), std::sqrt(5.0 / 56.0));
}

// A species drawn in its own region (a rough chute base of frozen grains in a thin layer), and the
// checks of Lees-Edwards boundaries in the DEM engine.
TEST(CaseLoader, SpeciesRegionsAndDemLeesEdwardsAreChecked) {
  const std::string base = kMinimal + R"(
[[species]]
name = "base"
diameter = 0.003
density = 2490.0
count = 30
frozen = true
region_lo = [0.0, 0.0, 0.0]
region_hi = [0.02, 0.0045, 0.02]
)";
  const CaseConfig c = load_case_from_string(base, kLabel);
  ASSERT_TRUE(c.species[1].region_hi.has_value());
  EXPECT_EQ(c.species[1].region_hi->y, 0.0045);
  // Its centres lie a radius inside the region's bounded extent, the others' outside it too.
  const dem::DemState s = dem::build_dem_state(c);
  int in_base = 0;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    if (s.particles.motion[i] != Motion::frozen) continue;
    ++in_base;
    EXPECT_GE(s.particles.position[i].y, 0.0015 - 1e-15);
    EXPECT_LE(s.particles.position[i].y, 0.0030 + 1e-15);
    EXPECT_EQ(s.particles.radius[i], 0.0015) << "a fixed grain keeps its size (fixed grains may overlap)";
  }
  EXPECT_EQ(in_base, 30);
  expect_input_error(replace(base, "region_hi = [0.02, 0.0045, 0.02]\n", ""), "species.1.region_hi",
                     "needs both region_lo and region_hi");
  expect_input_error(replace(base, "init = \"random\"", "init = \"lattice\""), "species.region_lo",
                     "init = \"random\"");
  expect_input_error(replace(base, "region_hi = [0.02, 0.0045, 0.02]", "region_hi = [0.02, 0.0025, 0.02]"),
                     "species.region_hi", "wider than the largest diameter");

  const std::string sheared = replace(replace(replace(kMinimal, "y = [\"wall\", \"open\"]", "y = \"periodic\""),
                                              "[0.0, -9.81, 0.0]", "[0.0, 0.0, 0.0]"),
                                      "[walls.ylo]\nrestitution = 0.8\nfriction = 0.3\n", "") +
                              "\n[lees_edwards]\nshear_rate = 100.0\n";
  EXPECT_EQ(load_case_from_string(sheared, kLabel).lees_edwards_rate, 100.0);
  expect_input_error(replace(sheared, "[0.0, 0.0, 0.0]\n\n[[species]]", "[0.0, -9.81, 0.0]\n\n[[species]]"),
                     "gravity.vector", "only act along z");
  expect_input_error(replace(sheared, "hi = [0.02, 0.05, 0.02]", "hi = [0.012, 0.05, 0.02]"), "domain.hi",
                     "4 list cutoffs");
  expect_input_error(sheared + "\n[coarse_grain]\n", "coarse_grain", "Lees-Edwards");
}
