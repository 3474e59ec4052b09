// Numerical faults that no valid case file reaches: a non-finite DEM or EDMD state, and
// an EDMD particle beyond a wall (the engine's exact flights keep one inside). The runs are driven
// with a state the loader would refuse; each must stop with a message naming the particle, the
// simulated time and the likely cause, exit status 1 and leave valid outputs. The faults a case
// file can provoke are tested end to end in tests/integration/test_numerical_faults.py.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <unistd.h>
#include <variant>

#include "grainflow/run/dem_run.hpp"
#include "grainflow/run/edmd_run.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/dem/fault_checks.hpp"
#include "grainflow/edmd/edmd_state.hpp"
#include "grainflow/edmd/fault_checks.hpp"

namespace grainflow {
namespace {

namespace fs = std::filesystem;

// A fresh folder under the system's temporary one, removed at the end of the test.
struct TempFolder {
  fs::path path;
  explicit TempFolder(const std::string& name)
      : path(fs::temp_directory_path() / ("grainflow_faults_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempFolder() { fs::remove_all(path); }
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Lines of a CSV output that are not comments: the header and at least `min_rows` rows, each as
// many fields as the header.
void expect_valid_csv(const fs::path& path, long min_rows) {
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::string line;
  long rows = 0;
  std::size_t fields = 0;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t n = std::count(line.begin(), line.end(), ',') + 1;
    if (rows++ == 0) fields = n;
    else EXPECT_EQ(n, fields) << path << ": " << line;
  }
  EXPECT_GE(rows, 1 + min_rows) << path;
}

// 3 glass spheres in a box with a floor, from a particle file (the loader checks it is finite).
CaseConfig dem_case(const TempFolder& folder) {
  std::ofstream(folder.path / "particles.csv") << "species,x,y,z,vx,vy,vz\n"
                                                  "glass,0.003,0.005,0.003,0,0,0\n"
                                                  "glass,0.008,0.005,0.003,0,0,0\n"
                                                  "glass,0.003,0.005,0.008,0,0,0\n";
  const std::string text = R"([engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.012, 0.02, 0.012]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0

[particles]
init = "file"
file = ")" + (folder.path / "particles.csv").string() +
                           R"("

[contact]
k1 = 1.0e6
restitution = 0.9

[run]
duration = 0.001

[output]
interval = 0.0002
)";
  return load_case_from_string(text, (folder.path / "case.toml").string());
}

TEST(FaultChecks, DemEngineNamesTheParticleStepAndTimeOfANonFiniteState) {
  TempFolder folder("dem_engine");
  const CaseConfig c = dem_case(folder);
  dem::DemEngineVariant engine = dem::make_engine(c, dem::build_dem_state(c), 1);
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < 3; ++k) e.step();
        auto& p = e.state().particles;
        std::size_t i = 0;
        while (p.id[i] != 1) ++i;
        p.velocity[i].y = std::numeric_limits<double>::quiet_NaN();  // e.g. a force gone infinite
        try {
          e.step();
          FAIL() << "a NaN velocity did not stop the engine";
        } catch (const dem::NonFiniteState& fault) {
          const std::string message = fault.what();
          EXPECT_NE(message.find("particle 1 at ("), std::string::npos) << message;
          EXPECT_NE(message.find("moving at (0, nan, 0) m/s"), std::string::npos) << message;
          EXPECT_NE(message.find("(step 4)"), std::string::npos) << message;
          EXPECT_NE(message.find("t = "), std::string::npos) << message;
          // The run adds the cause: eq. (2-5-4) with n = 20 and its numbers.
          const dem::DerivedQuantities d = dem::derive(c);
          const std::string full = dem::with_cause(fault, d);
          EXPECT_NE(full.find("time step dt = "), std::string::npos) << full;
          EXPECT_NE(full.find("is too large for k1 = 1e+06 N/m"), std::string::npos) << full;
          char suggested[64];
          std::snprintf(suggested, sizeof suggested, "suggests dt <= %.4g s",
                        dem::WaltonBraun::time_step(dem::WaltonBraun::make(1.0e6, 0.9, 1.0, 0.0),
                                                    {0.5 * d.reference_mass, 0.0, 0.0}, 20));
          EXPECT_NE(full.find("time-step bound with n = 20 steps per collision"), std::string::npos) << full;
          EXPECT_NE(full.find(suggested), std::string::npos) << full << " lacks " << suggested;
        }
      },
      engine);
}

TEST(FaultChecks, DemRunWithANonFiniteStateExitsWithStatusOneAndValidOutputs) {
  TempFolder folder("dem_run");
  CaseConfig c = dem_case(folder);
  c.initial_particles[2].velocity.x = std::numeric_limits<double>::infinity();  // refused by the loader
  run::RunOptions options;
  options.output_directory = (folder.path / "out").string();
  options.quiet = true;
  options.echo_errors = false;
  EXPECT_EQ(run::run_dem(c, options), 1);
  const std::string summary = read_text(folder.path / "out" / "summary.json");
  EXPECT_NE(summary.find("\"errors\": [\"non-finite state: particle 2 at ("), std::string::npos) << summary;
  EXPECT_NE(summary.find("at t = 0 s (step 0)"), std::string::npos) << summary;
  EXPECT_NE(summary.find("likely cause: the time step dt = "), std::string::npos) << summary;
  expect_valid_csv(folder.path / "out" / "timeseries.csv", 0);  // found at t = 0, before the first row
  expect_valid_csv(folder.path / "out" / "final_state.csv", static_cast<long>(c.initial_particles.size()));
}

// 6 discs in a 2D box with a floor, at rest on a lattice.
CaseConfig edmd_case() {
  return load_case_from_string(R"([engine]
kind = "edmd"
dimension = 2

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.05, 0.01]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[gravity]
vector = [0.0, 0.0, 0.0]

[[species]]
name = "disc"
diameter = 0.002
density = 2.0
count = 6

[particles]
init = "lattice"
initial_temperature = 0.01
seed = 3

[collision]
restitution = 0.9

[run]
duration = 0.05

[output]
interval = 0.01
)",
                               "edmd_case.toml");
}

TEST(FaultChecks, EdmdParticleBeyondAWallIsNamedWithFaceAndTime) {
  edmd::EdmdState s = edmd::build_edmd_state(edmd_case());
  s.time = 0.25;
  s.particles.position[4].y = -0.005;  // 2.5 diameters under the floor
  try {
    edmd::check_faults(s);
    FAIL() << "a particle under the floor was not found";
  } catch (const RunError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("particle " + std::to_string(s.particles.id[4]) + " at ("), std::string::npos) << message;
    EXPECT_NE(message.find("went through the ylo wall at t = 0.25 s"), std::string::npos) << message;
    EXPECT_NE(message.find("likely cause: a missed wall event"), std::string::npos) << message;
  }
  s.particles.position[4].y = 0.0005;  // overlapping the floor by half a radius: not an escape
  EXPECT_NO_THROW(edmd::check_faults(s));
}

TEST(FaultChecks, EdmdRunWithANonFiniteStateExitsWithStatusOneAndValidOutputs) {
  TempFolder folder("edmd_run");
  CaseConfig c = edmd_case();
  // A file's particles instead of the lattice, one with a NaN velocity (refused by the loader).
  edmd::EdmdState s = edmd::build_edmd_state(c);
  c.particles.init = "file";
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    c.initial_particles.push_back({"disc", s.particles.position[i], s.particles.velocity[i], {}, 0.0});
  c.initial_particles[3].velocity.x = std::numeric_limits<double>::quiet_NaN();
  run::RunOptions options;
  options.output_directory = (folder.path / "out").string();
  options.quiet = true;
  options.echo_errors = false;
  EXPECT_EQ(run::run_edmd(c, options), 1);
  const std::string summary = read_text(folder.path / "out" / "summary.json");
  EXPECT_NE(summary.find("\"errors\": [\"non-finite state: particle 3 at ("), std::string::npos) << summary;
  EXPECT_NE(summary.find("at t = 0 s; likely cause:"), std::string::npos) << summary;
  expect_valid_csv(folder.path / "out" / "timeseries.csv", 0);  // found at t = 0, before the first row
  expect_valid_csv(folder.path / "out" / "final_state.csv", static_cast<long>(c.initial_particles.size()));
}

}  // namespace
}  // namespace grainflow
