// Cross-check against LAMMPS: cases/bench/chute_hooke.toml runs LAMMPS's bench/in.chute (same
// particles, gran/hooke/history parameters, time step, skin). After its 100 steps LAMMPS reports
// total translational kinetic energy 784292.08 and rotational 1571.0968 (its shipped 2016 log and a
// build made here agree; ../shared/bench/README.md). 100 steps of a dense flow amplify round-off
// differences (summation order) only slightly, so 1e-6 relative is a demanding but fair tolerance
// for "the same physics": any modelling difference (damping, history update, frozen-partner mass,
// gravity, integrator) shows up at 1e-5 or above.
#include <gtest/gtest.h>

#include <filesystem>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/observe/global_sample.hpp"

using namespace grainflow;

TEST(LammpsChute, KineticEnergiesAfter100StepsMatchLammps) {
  const std::string case_path = std::string(GRAINFLOW_SOURCE_DIR) + "/cases/bench/chute_hooke.toml";
  const std::string data = std::string(GRAINFLOW_SOURCE_DIR) + "/../shared/bench/chute_32k.csv";
  if (!std::filesystem::exists(data)) GTEST_SKIP() << "benchmark particles not present: " << data;
  const CaseConfig c = load_case(case_path);
  auto engine = dem::make_engine(c, dem::build_dem_state(c), 1);
  std::visit(
      [&](auto& e) {
        for (int step = 0; step < 100; ++step) e.step();
        const auto global = observe::sample_global(e.state().particles, 2, 3);
        EXPECT_NEAR(global.kinetic_energy, 784292.08, 784292.08 * 1e-6);
        EXPECT_NEAR(global.rotational_energy, 1571.0968, 1571.0968 * 1e-6);
      },
      engine);
}
