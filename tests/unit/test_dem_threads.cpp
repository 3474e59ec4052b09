// The soft-sphere engine's forces do not depend on the thread count (dem_engine.hpp: each thread
// adds to its own range of particles and buffers its shares for the others'): a settled frictional
// pile on a shaken floor, evaluated with 1, 2 and 3 threads, gives every particle the same force
// and torque to round-off (summation order only: 1e-12 of the largest), and the same contacts,
// at once and after 5 more steps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/dem/engine_factory.hpp"

using namespace grainflow;

namespace {

// 600 spheres on a square lattice at contact spacing, with friction; Walton-Braun or the linear
// spring-dashpot.
std::string pile_case(const std::string& model) {
  const bool walton_braun = model == "walton_braun";
  const std::string contact = walton_braun ? "k1 = 1.0e5\nrestitution = 0.8\nfriction = 0.4\n"
                                           : "kn = 1.0e5\ngamma_n = 0.3\nfriction = 0.4\n";
  const std::string wall = walton_braun ? "restitution = 0.8\nfriction = 0.4\n" : "gamma_n = 0.3\nfriction = 0.4\n";
  return std::string(R"([engine]
kind = "dem"
dimension = 3
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.024, 0.06, 0.024]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.0, -9.81, 0.0]
[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 600
[particles]
init = "lattice"
lattice_spacing = 1.0
region_hi = [0.024, 0.04, 0.024]
initial_temperature = 1.0e-3
seed = 3
[contact]
model = ")") + model + "\"\n" + contact + "[walls.ylo]\n" + wall + R"([drive]
face = "ylo"
amplitude = [0.0, 0.002, 0.0]
frequency = [0.0, 20.0, 0.0]
[run]
duration = 0.01
time_step = 5.0e-6
)";
}

struct Forces {
  std::vector<Vec3> force, torque;
  long contacts = 0;
};

// The forces that an engine on `threads` threads computes from `state`, and after `steps` more steps.
Forces forces(const CaseConfig& c, const dem::DemState& state, int threads, int steps) {
  auto engine = dem::make_engine(c, state, threads);
  Forces f;
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < steps; ++k) e.step();
        f.force = e.state().particles.force;
        f.torque = e.state().particles.torque;
        f.contacts = e.statistics().contacts;
      },
      engine);
  return f;
}

double largest(const std::vector<Vec3>& v) {
  double m = 0.0;
  for (const Vec3& x : v) m = std::max(m, norm(x));
  return m;
}

// A settled state: the pile after 400 one-thread steps (2 ms), compressed under its weight, its
// contacts well inside their overlaps. (Comparing long runs instead would test nothing: a contact
// that begins one step earlier through round-off restarts its tangential history, so frictional
// runs part visibly whatever the summation order.)
dem::DemState settled(const CaseConfig& c) {
  auto engine = dem::make_engine(c, dem::build_dem_state(c), 1);
  dem::DemState state;
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < 400; ++k) e.step();
        state = e.state();
      },
      engine);
  return state;
}

void expect_same_forces(const std::string& model) {
  const CaseConfig c = load_case_from_string(pile_case(model), "threads_test.toml");
  const dem::DemState state = settled(c);
  for (int steps : {0, 5}) {
    const Forces one = forces(c, state, 1, steps);
    ASSERT_GT(one.contacts, 500) << model << ": the pile should be in contact (600 particles)";
    const double f_scale = largest(one.force), t_scale = largest(one.torque);
    for (int threads : {2, 3}) {
      const Forces many = forces(c, state, threads, steps);
      EXPECT_EQ(one.contacts, many.contacts) << model << ", " << threads << " threads";
      double f_diff = 0.0, t_diff = 0.0;
      for (std::size_t i = 0; i < one.force.size(); ++i) {
        f_diff = std::max(f_diff, norm(one.force[i] - many.force[i]));
        t_diff = std::max(t_diff, norm(one.torque[i] - many.torque[i]));
      }
      EXPECT_LE(f_diff, 1e-12 * f_scale) << model << ", " << threads << " threads, step " << steps;
      EXPECT_LE(t_diff, 1e-12 * t_scale) << model << ", " << threads << " threads, step " << steps;
    }
  }
}

}  // namespace

TEST(DemThreads, WaltonBraunForcesDoNotDependOnTheThreadCount) { expect_same_forces("walton_braun"); }

TEST(DemThreads, LinearDashpotForcesDoNotDependOnTheThreadCount) { expect_same_forces("linear_dashpot"); }
