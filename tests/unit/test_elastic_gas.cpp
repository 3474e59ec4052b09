// Elastic gas: frictionless spheres with restitution 1 (K2 = K1, so the Walton–Braun law is a
// plain linear spring) in a fully periodic box with no gravity. Newton's third law makes total
// momentum a round-off quantity; velocity Verlet keeps the total energy (kinetic + spring) with
// an error that shrinks as dt^2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <variant>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "test_support.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

// 216 spheres (d = 2 mm, 2500 kg/m^3) on a 6^3 lattice filling a periodic cube of 8.4 d (solids
// fraction 0.19), thermalised at T = 0.1 m^2/s^2 (rms speed ~0.55 m/s: overlaps ~1% d with
// K1 = 1e4 N/m), fixed seed. A sphere collides about every 20 contact durations.
std::string gas_case(int collision_steps, int seed) {
  char text[2048];
  std::snprintf(text, sizeof text, R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.0168, 0.0168, 0.0168]
boundary = { x = "periodic", y = "periodic", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
count = 216
[particles]
init = "lattice"
lattice_spacing = 1.399
initial_temperature = 0.1
seed = %d
[contact]
model = "walton_braun"
k1 = 1.0e4
restitution = 1.0
friction = 0.0
[run]
duration = 1.0
collision_steps = %d
)",
                seed, collision_steps);
  return text;
}

struct GasRun {
  double max_energy_error = 0.0;    // max |E - E0| / E0 over the run
  double rms_increment = 0.0;       // rms of E(t + t_c) - E(t) / E0, sampled every contact duration
  long intervals = 0;               // number of those samples
  double max_momentum_error = 0.0;  // max |P - P0| / sum m |v|
  long contact_steps = 0;           // touching pairs summed over all steps
  double time_step = 0.0;
};

GasRun run_gas(int collision_steps, double duration, int seed) {
  const CaseConfig c = load_case_from_string(gas_case(collision_steps, seed), "gas.toml");
  auto engine = test::engine_for(c, 1);
  GasRun out;
  std::visit(
      [&](auto& e) {
        const auto& p = e.state().particles;
        const double k1 = c.contact.parameters.at("k1");
        const std::size_t n = p.size();
        auto energy = [&] {
          double kinetic = 0.0, spring = 0.0;
          for (std::size_t i = 0; i < n; ++i) kinetic += 0.5 * p.mass[i] * norm2(p.velocity[i]);
          // Every touching pair is on the engine's half neighbor list (it keeps a skin), once.
          const auto& pairs = e.pairs();
          const auto shifts = e.state().box.shift_table();
          for (std::size_t i = 0; i < n; ++i)
            for (std::uint32_t k = pairs.offsets[i]; k < pairs.offsets[i + 1]; ++k) {
              const std::uint32_t j = pairs.partner[k];
              const double overlap =
                  p.radius[i] + p.radius[j] - norm(p.position[i] - p.position[j] - shifts[pairs.shift[k]]);
              if (overlap > 0.0) spring += 0.5 * k1 * overlap * overlap;
            }
          return kinetic + spring;
        };
        auto momentum = [&] {
          Vec3 total;
          double scale = 0.0;
          for (std::size_t i = 0; i < n; ++i) {
            total += p.mass[i] * p.velocity[i];
            scale += p.mass[i] * norm(p.velocity[i]);
          }
          return std::pair{total, scale};
        };
        const double e0 = energy();
        const auto [p0, scale0] = momentum();
        out.time_step = e.state().time_step;
        const long steps = std::lround(duration / out.time_step);
        double last = e0, sum_squares = 0.0;
        for (long k = 0; k < steps; ++k) {
          e.step();
          const double now = energy();
          if ((k + 1) % collision_steps == 0) {
            sum_squares += (now - last) * (now - last);
            last = now;
            ++out.intervals;
          }
          out.contact_steps += e.statistics().contacts;
          out.max_energy_error = std::max(out.max_energy_error, std::fabs(now - e0) / e0);
          const auto [pk, scale] = momentum();
          out.max_momentum_error = std::max(out.max_momentum_error, norm(pk - p0) / scale0);
        }
        out.rms_increment = std::sqrt(sum_squares / out.intervals) / e0;
      },
      engine);
  return out;
}

}  // namespace

// Newton's third law in the pair loop (force[i] += F, force[j] -= F) conserves the total momentum
// exactly up to round-off. Each step adds errors of order 1e-16 of the momentum scale sum m|v|; a
// random walk over ~6000 steps stays below 1e-14, so 1e-12 leaves a wide margin while any missing
// or doubled pair force (even one contact's worth: ~1e-3 of the scale) fails.
TEST(ElasticGas, MomentumConservedToRoundOff) {
  const GasRun run = run_gas(15, 0.03, 1);
  EXPECT_GT(run.contact_steps, 10000);  // ~2000 collisions of 15 steps each: not a trivial run
  EXPECT_LT(run.max_momentum_error, 1e-12);
}

// Energy: the total (kinetic + K1 overlap^2 / 2 over touching pairs) is conserved by the dynamics,
// and velocity Verlet errs by O((omega dt)^2) on every contact. The signal is the change of E over
// one contact duration t_c, sampled every t_c (= n steps at collision_steps = n, e = 1): its rms
// sums thousands of independent collision errors, so its ratio between n and 2n is a clean
// convergence test (measured 3.4 .. 4.8 on 40 single seeds, 3.8 .. 4.3 on averages of 4 seeds).
// A second-order integrator gives 4, a first-order one 2 and third order 8: the ratio of the rms
// over 3 seeds must lie in [2^1.5, 2^2.5] = [2.83, 5.66], i.e. an observed order of 2 +- 0.5.
// The drift itself must not be systematic: max |E - E0| stays within 4 rms-increments times the
// square root of the number of intervals (a zero-mean random walk exceeds that with probability
// ~1e-4), and below 5e-3 E0 at n = 15 (measured <= 1.1e-3 over 10 seeds).
TEST(ElasticGas, EnergyErrorShrinksAsTimeStepSquared) {
  double coarse_squares = 0.0, fine_squares = 0.0;
  for (int seed : {1, 2, 3}) {
    const GasRun coarse = run_gas(15, 0.03, seed);
    const GasRun fine = run_gas(30, 0.03, seed);
    coarse_squares += coarse.rms_increment * coarse.rms_increment;
    fine_squares += fine.rms_increment * fine.rms_increment;
    for (const GasRun* run : {&coarse, &fine}) {
      EXPECT_LT(run->max_energy_error, 4.0 * run->rms_increment * std::sqrt(run->intervals)) << "seed " << seed;
      EXPECT_LT(run->max_energy_error, 5e-3) << "seed " << seed;
    }
    EXPECT_GT(coarse.contact_steps, 10000);
  }
  const double ratio = std::sqrt(coarse_squares / fine_squares);
  EXPECT_GT(ratio, 2.83);
  EXPECT_LT(ratio, 5.66);
}
