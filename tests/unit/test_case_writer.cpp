// The case writer (core/case_writer.hpp) behind OUTDIR/resolved_case.toml: loading what it writes
// gives the same CaseConfig, field for field (CaseConfig's defaulted ==), for every bundled case and
// for cases that set the keys the bundled ones leave at their defaults.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/config/case_writer.hpp"

using namespace grainflow;
namespace fs = std::filesystem;

namespace {

// Loads the written text of `c` and requires the same config (but for where it came from, and
// particles.file, written as the same file's absolute path).
void expect_round_trip(CaseConfig c) {
  const std::string text = write_case_toml(c);
  CaseConfig again = load_case_from_string(text, "resolved_case.toml");
  again.path = c.path;
  again.overrides = c.overrides;
  if (c.particles.init == "file") {
    EXPECT_TRUE(fs::path(again.particles.file).is_absolute()) << again.particles.file;
    EXPECT_TRUE(fs::equivalent(again.particles.file, c.particles.file)) << again.particles.file;
    c.particles.file = again.particles.file;
  }
  EXPECT_TRUE(again == c) << c.path << " does not survive the round trip; written as:\n" << text;
  EXPECT_EQ(write_case_toml(again), text) << c.path << ": writing the reloaded case gives another text";
}

// Every key the bundled cases leave at its default, set: Hertz properties, ratk, a bumpy wall with a
// triangular lattice, a drive with explicit phases, regions, every sampled output with particle ids.
const std::string kDemEverything = R"([engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.05, 0.02]
boundary = { x = "periodic", y = ["bumpy", "wall"], z = "periodic" }

[gravity]
vector = [0.1, -9.81, 0.0]

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 20
youngs_modulus = 6.3e10
poisson_ratio = 0.21

[[species]]
name = "big"
diameter = 0.004
density = 2000.0
count = 1
position = [0.01, 0.01, 0.01]

[particles]
init = "random"
seed = 17
initial_temperature = 0.01
region_lo = [0.0, 0.004, 0.0]
region_hi = [0.02, 0.045, 0.02]
expansion_time = 0.02
initial_velocity = [0.1, 0.0, 0.0]

[contact]
k1 = 1.0e6
restitution = 0.85
ratk = 0.7
friction = 0.4

[walls.ylo]
restitution = 0.8
friction = 0.3
bump_diameter = 0.0035
lattice = "triangular"
spacing = 0.004

[walls.yhi]
velocity = [0.05, 0.0, 0.0]

[drive]
face = "ylo"
amplitude = [0.0001, 0.002, 0.0]
frequency = [20.0, 25.0, 0.0]
phase = [0.5, 0.0, 0.0]
start = 0.01
ramp = 0.02

[run]
duration = 0.1
time_step = 2.0e-6
collision_steps = 12
skin = 0.0004
halt_overlap = 0.02
sort_every = 7

[output]
interval = 0.002
snapshot_interval = 0.01
profile_interval = 0.0005
average_start = 0.03
zone_thickness = 0.0025
bed_gap_fraction = 0.07
bed_surface_fraction = 0.2

[trajectory]
start = 0.04
window = 1.0e-4
samples = 100
max_lag = 30
particles = [0, 3, 5]

[zone_series]
start = 0.05
interval = 0.002
samples = 32

[field]
axis = "x"
cell = 0.004
start = 0.06
interval = 0.001
phase_bins = 4

[tracers]
particles = [1, 2]
species = ["big"]
start = 0.01
interval = 0.003

[coarse_grain]
kernel = "gaussian"
width = 0.0025
cells = [5, 25, 5]
start = 0.05
interval = 0.001
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in the case text";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

}  // namespace

// The bundled cases, those that read the LAMMPS benchmark's particles (../shared/bench/) or not.
std::vector<fs::path> bundled_cases(bool lammps_benchmark) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(fs::path(GRAINFLOW_SOURCE_DIR) / "cases")) {
    if (entry.path().extension() != ".toml") continue;
    std::ifstream in(entry.path());
    const std::string text(std::istreambuf_iterator<char>(in), {});
    if ((text.find("shared/bench/") != std::string::npos) == lammps_benchmark) out.push_back(entry.path());
  }
  return out;
}

TEST(CaseWriter, EveryBundledCaseSurvivesTheRoundTrip) {
  const auto cases = bundled_cases(false);
  for (const auto& path : cases) {
    SCOPED_TRACE(path.string());
    expect_round_trip(load_case(path.string()));
  }
  EXPECT_GT(cases.size(), 20u);
}

// A bare clone (CI) lacks ../shared/bench/: reported as skipped, not passed.
TEST(CaseWriter, TheLammpsBenchmarkCasesSurviveTheRoundTrip) {
  if (!fs::exists(fs::path(GRAINFLOW_SOURCE_DIR) / ".." / "shared" / "bench"))
    GTEST_SKIP() << "the LAMMPS benchmark's particles (../shared/bench/) are not present";
  const auto cases = bundled_cases(true);
  for (const auto& path : cases) {
    SCOPED_TRACE(path.string());
    expect_round_trip(load_case(path.string()));
  }
  EXPECT_GE(cases.size(), 2u);
}

TEST(CaseWriter, KeysTheBundledCasesLeaveAtTheirDefaults) {
  expect_round_trip(load_case_from_string(kDemEverything, "everything.toml"));
  // --set overrides are baked in.
  const CaseConfig set =
      load_case_from_string(kDemEverything, "everything.toml", {"contact.friction=0.1", "run.sort_every=3"});
  expect_round_trip(set);
  EXPECT_NE(write_case_toml(set).find("friction = 0.1\n"), std::string::npos);
  // The rotary preset (its phases fixed) and the linear dashpot with a wall damping.
  const std::string rotary =
      replace(replace(kDemEverything,
                      "amplitude = [0.0001, 0.002, 0.0]\nfrequency = [20.0, 25.0, 0.0]\nphase = [0.5, 0.0, 0.0]",
                      "preset = \"rotary\"\namplitude = [0.001, 0.001, 0.001]\nfrequency = [20.0, 20.0, 20.0]"),
              "k1 = 1.0e6\nrestitution = 0.85\nratk = 0.7", "model = \"linear_dashpot\"\nkn = 2.0e5\ngamma_n = 300.0");
  expect_round_trip(load_case_from_string(
      replace(rotary, "restitution = 0.8\nfriction = 0.3", "gamma_n = 200.0\nfriction = 0.3"), "rotary.toml"));
  // Lucy's kernel, sized by its cutoff, on the default grid.
  expect_round_trip(
      load_case_from_string(replace(kDemEverything, "kernel = \"gaussian\"\nwidth = 0.0025\ncells = [5, 25, 5]",
                                    "kernel = \"lucy\"\ncutoff = 0.004"),
                            "lucy.toml"));
}

TEST(CaseWriter, DoublesAreWrittenExactly) {
  // Values with no short decimal form must come back bit for bit (shortest round-trip digits).
  const std::string text = replace(kDemEverything, "restitution = 0.85", "restitution = 0.8500000000000001");
  const CaseConfig c = load_case_from_string(text, "exact.toml");
  EXPECT_EQ(load_case_from_string(write_case_toml(c), "again.toml").contact.parameters.at("restitution"),
            0.8500000000000001);
}
