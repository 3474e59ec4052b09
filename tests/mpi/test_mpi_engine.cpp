// The soft-sphere engine's failure paths on two MPI ranks, run by ctest under
// `mpirun --oversubscribe -np 2`: a fault one rank finds inside a step must stop every rank at the
// same step (the others would otherwise wait for it in the next exchange), and the run must then
// write its outputs with the faulty rank's message. The faults cannot come from a valid case file
// (the loader refuses non-finite numbers), so the state is broken by hand, as in test_fault_checks.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <unistd.h>
#include <variant>

#include "grainflow/run/dem_parallel_view.hpp"
#include "grainflow/run/dem_run.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/fault_checks.hpp"
#include "grainflow/parallel/communicator.hpp"

namespace grainflow {
namespace {

namespace fs = std::filesystem;
const parallel::Communicator& comm() { return parallel::Communicator::world(); }

// One folder for all ranks (rank 0's process id, shared by a broadcast through a sum).
fs::path shared_folder(const std::string& name) {
  const long long pid = comm().sum(comm().root() ? static_cast<long long>(::getpid()) : 0LL);
  return fs::temp_directory_path() / ("grainflow_mpi_" + name + "_" + std::to_string(pid));
}

// 6 rough glass spheres at rest on a floor, 3 at each end of the periodic x axis, so each of two slabs
// owns some.
CaseConfig resting_case(const fs::path& folder) {
  if (comm().root()) {
    fs::create_directories(folder);
    std::ofstream(folder / "particles.csv") << "species,x,y,z,vx,vy,vz,wx,wy,wz\n"
                                               "glass,0.002,0.0014,0.003,0,0,0,0,0,0\n"
                                               "glass,0.002,0.0014,0.009,0,0,0,0,0,0\n"
                                               "glass,0.005,0.0014,0.006,0,0,0,0,0,0\n"
                                               "glass,0.014,0.0014,0.003,0,0,0,0,0,0\n"
                                               "glass,0.017,0.0014,0.009,0,0,0,0,0,0\n"
                                               "glass,0.020,0.0014,0.006,0,0,0,0,0,0\n";
  }
  comm().any(false);  // a barrier: the file exists before any rank reads it
  const std::string text = R"([engine]
kind = "dem"

[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.024, 0.02, 0.012]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }

[[species]]
name = "glass"
diameter = 0.003
density = 2490.0

[particles]
init = "file"
file = ")" + (folder / "particles.csv").string() +
                           R"("

[contact]
k1 = 1.0e6
restitution = 0.9
friction = 0.5

[run]
duration = 0.002

[output]
interval = 0.0005
)";
  return load_case_from_string(text, (folder / "case.toml").string());
}

TEST(MpiEngine, ANonFiniteStateOnOneRankStopsEveryRankAtTheSameStep) {
  ASSERT_EQ(comm().size(), 2) << "run under mpirun -np 2";
  const fs::path folder = shared_folder("engine");
  const CaseConfig c = resting_case(folder);
  dem::DemState initial = dem::build_dem_state(c);
  const dem::EngineDomain domain{&comm(), run::dem_grid(initial, comm().size())};
  dem::DemEngineVariant engine = dem::make_engine(c, std::move(initial), 1, &domain);
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < 3; ++k) e.step();
        auto& p = e.state().particles;
        bool owner = false;
        for (std::size_t i = 0; i < p.size(); ++i)
          if (p.id[i] == 4 && !p.ghost[i]) {
            p.velocity[i].x = std::numeric_limits<double>::quiet_NaN();  // e.g. a force gone infinite
            owner = true;
          }
        EXPECT_EQ(comm().sum(owner ? 1LL : 0LL), 1) << "sphere 4 has exactly one owner";
        // Step 4 drifts it to a NaN position; its rank finds it at that step's rebuild test, and
        // every rank must throw there, not wait in an exchange (a hang would time the test out).
        std::string message;
        long stopped_at = -1;
        try {
          for (int k = 0; k < 5; ++k) e.step();
        } catch (const dem::NonFiniteState& fault) {
          message = fault.what();
          stopped_at = e.state().step;
        }
        EXPECT_EQ(stopped_at, 4);
        EXPECT_EQ(comm().max(static_cast<double>(stopped_at)), 4.0) << "the ranks stopped at different steps";
        if (owner) {
          EXPECT_NE(message.find("particle 4 at ("), std::string::npos) << message;
          EXPECT_NE(message.find("(step 4)"), std::string::npos) << message;
        } else {
          EXPECT_EQ(message, dem::kFaultOnAnotherRank);
        }
      },
      engine);
  if (comm().root()) fs::remove_all(folder);
}

TEST(MpiEngine, ARunWithANonFiniteStateOnOneRankWritesItsOutputsWithThatRanksMessage) {
  ASSERT_EQ(comm().size(), 2) << "run under mpirun -np 2";
  const fs::path folder = shared_folder("run");
  // A NaN spin passes the output-time checks (position and velocity), and reaches the velocity
  // through the floor contact's tangential force: the position turns NaN inside the first steps.
  CaseConfig c = resting_case(folder);
  c.initial_particles[4].angular_velocity.z = std::numeric_limits<double>::quiet_NaN();  // refused by the loader
  run::RunOptions options;
  options.output_directory = (folder / "out").string();
  options.quiet = true;
  options.echo_errors = false;
  EXPECT_EQ(run::run_dem(c, options), 1) << "on rank " << comm().rank();
  comm().any(false);  // rank 0 has written everything
  if (comm().root()) {
    std::ifstream in(folder / "out" / "summary.json");
    std::stringstream text;
    text << in.rdbuf();
    const std::string summary = text.str();
    EXPECT_NE(summary.find("non-finite state: particle 4 at ("), std::string::npos) << summary;
    EXPECT_NE(summary.find("likely cause: the time step"), std::string::npos) << summary;
    EXPECT_TRUE(fs::exists(folder / "out" / "final_state.csv"));
    EXPECT_TRUE(fs::exists(folder / "out" / "timeseries.csv"));
    fs::remove_all(folder);
  }
}

}  // namespace
}  // namespace grainflow

int main(int argc, char** argv) {
  grainflow::parallel::Communicator::start(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
