// Micro benchmarks of the DEM hot kernels: one contact-law evaluation (Walton–Braun with friction
// vs the linear spring–dashpot), a cell-grid neighbor build, and one full engine step; and the
// machine's two roofline ceilings as this compiler reaches them: a register-resident fused
// multiply-add loop (flops) and a STREAM triad over arrays far larger than the caches (bytes).
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
         "[[species]]\nname=\"g\"\ndiameter=1.0\ndensity=1.0\ncount=" +
         std::to_string(n) +
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

// Peak arithmetic: 64 independent multiply-add chains (eight 512-bit registers' worth, enough to
// cover the FMA latency on two pipes) that stay in registers; 2 flops each.
void BM_PeakMultiplyAdd(benchmark::State& bench) {
  constexpr int kChains = 64;
  alignas(64) double acc[kChains];
  for (int k = 0; k < kChains; ++k) acc[k] = 1.0 + 1e-3 * k;
  const double a = 0.999999, b = 1e-7;
  constexpr long kRounds = 4096;
  for (auto _ : bench) {
    for (long r = 0; r < kRounds; ++r)
#pragma omp simd
      for (int k = 0; k < kChains; ++k) acc[k] = acc[k] * a + b;
    benchmark::DoNotOptimize(acc);
  }
  bench.counters["flops"] = benchmark::Counter(static_cast<double>(bench.iterations()) * kRounds * kChains * 2.0,
                                               benchmark::Counter::kIsRate);
}
BENCHMARK(BM_PeakMultiplyAdd);

// Memory bandwidth: a[i] = b[i] + s c[i] over three arrays of 2^23 doubles (64 MiB each); 24 bytes
// moved per element as STREAM counts them (the write's cache-line fill is not counted).
void BM_StreamTriad(benchmark::State& bench) {
  const std::size_t n = std::size_t{1} << 23;
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  const double s = 3.0;
  for (auto _ : bench) {
    double* __restrict pa = a.data();
    const double* __restrict pb = b.data();
    const double* __restrict pc = c.data();
    for (std::size_t i = 0; i < n; ++i) pa[i] = pb[i] + s * pc[i];
    benchmark::DoNotOptimize(a.data());
    benchmark::ClobberMemory();
  }
  bench.SetBytesProcessed(static_cast<long long>(bench.iterations()) * static_cast<long long>(n) * 24);
}
BENCHMARK(BM_StreamTriad)->Unit(benchmark::kMillisecond);

}  // namespace
