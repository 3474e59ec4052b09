// Micro benchmarks of the DEM hot kernels: one contact-law evaluation (Walton–Braun with friction
// vs the linear spring–dashpot), a cell-grid neighbor build, and one full engine step.
#include <benchmark/benchmark.h>

#include <random>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/dem/engine_factory.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

ContactKinematics sample_contact(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ContactKinematics c;
  c.normal = Vec3{u(rng), u(rng), u(rng)};
  c.normal *= 1.0 / norm(c.normal);
  c.overlap = 1e-3 * (1.5 + u(rng));
  c.normal_velocity = 0.1 * u(rng);
  c.slip_velocity = Vec3{u(rng), u(rng), u(rng)} * 0.1;
  c.slip_velocity -= dot(c.slip_velocity, c.normal) * c.normal;
  c.effective_mass = 0.26;
  return c;
}

template <class Law>
void contact_law(benchmark::State& bench, typename Law::Params params) {
  std::mt19937_64 rng(1);
  std::vector<ContactKinematics> contacts(1024);
  for (auto& c : contacts) c = sample_contact(rng);
  std::vector<typename Law::State> states(contacts.size());
  for (auto _ : bench) {
    for (std::size_t k = 0; k < contacts.size(); ++k) {
      const ContactForce f = Law::force(params, states[k], contacts[k], 1e-4);
      benchmark::DoNotOptimize(f);
    }
  }
  bench.SetItemsProcessed(bench.iterations() * contacts.size());
}

void BM_WaltonBraunFriction(benchmark::State& bench) {
  contact_law<WaltonBraun>(bench, WaltonBraun::make(2e5, 0.9, 0.8, 0.5));
}
void BM_LinearDashpot(benchmark::State& bench) {
  contact_law<LinearDashpot>(bench, LinearDashpot::Params{2e5, 2e5 * 2.0 / 7.0, 50.0, 0.0, 0.5});
}
BENCHMARK(BM_WaltonBraunFriction);
BENCHMARK(BM_LinearDashpot);

// A periodic gas at solids fraction ~0.3 with N particles.
std::string gas_case(long n) {
  const double side = std::cbrt(n * M_PI / 6.0 / 0.3);
  return "[domain]\nlo=[0,0,0]\nhi=[" + std::to_string(side) + "," + std::to_string(side) + "," + std::to_string(side) +
         "]\nboundary={x=\"periodic\",y=\"periodic\",z=\"periodic\"}\n[gravity]\nvector=[0,0,0]\n"
         "[[species]]\nname=\"g\"\ndiameter=1.0\ndensity=1.0\ncount=" + std::to_string(n) +
         "\n[particles]\ninit=\"lattice\"\ninitial_temperature=1.0\nlattice_spacing=1.0\n"
         "[contact]\nmodel=\"linear_dashpot\"\nkn=2e5\ngamma_n=50\nfriction=0.5\n"
         "[run]\nduration=1\ntime_step=1e-4\nskin=0.1\n";
}

void BM_NeighborBuild(benchmark::State& bench) {
  const CaseConfig c = load_case_from_string(gas_case(bench.range(0)), "bench.toml");
  DemState s = build_dem_state(c);
  CellGrid grid;
  grid.setup(s.box, 1.1, s.particles.size());
  NeighborPairs pairs;
  for (auto _ : bench) {
    grid.bin(s.particles.position);
    grid.build_pairs(s.particles, s.box, 0.1, 1, pairs);
    benchmark::DoNotOptimize(pairs.partner.data());
  }
  bench.SetItemsProcessed(bench.iterations() * bench.range(0));
}
BENCHMARK(BM_NeighborBuild)->Arg(4000)->Arg(32000);

void BM_EngineStep(benchmark::State& bench) {
  const CaseConfig c = load_case_from_string(gas_case(bench.range(0)), "bench.toml");
  auto engine = make_engine(c, build_dem_state(c), 1);
  for (auto _ : bench) std::visit([](auto& e) { e.step(); }, engine);
  bench.SetItemsProcessed(bench.iterations() * bench.range(0));
}
BENCHMARK(BM_EngineStep)->Arg(4000)->Arg(32000);

}  // namespace
