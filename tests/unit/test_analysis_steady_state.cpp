// Campbell's convergence indicator made objective (src/grainflow/analysis/steady_state.hpp) on
// synthetic kinetic-energy histories with fixed seeds: an exponential relaxation in noise is found
// steady where the transient has sunk to the noise, a steadily accelerating flow (Campbell's 40
// degree chute) never, a stationary correlated series from its start; and too short a series is
// refused with a reason.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "grainflow/analysis/steady_state.hpp"

using namespace grainflow::analysis;

namespace {

// AR(1) noise of marginal standard deviation sigma and lag-1 correlation phi.
std::vector<double> ar1_noise(std::size_t n, double phi, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<double> x(n);
  double v = sigma * g(rng);
  for (double& s : x) {
    s = v;
    v = phi * v + sigma * std::sqrt(1.0 - phi * phi) * g(rng);
  }
  return x;
}

std::vector<double> times(std::size_t n, double dt) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = i * dt;
  return t;
}

}  // namespace

// E(t) = E_inf + A exp(-t/tau) + noise sigma, white. The transient sinks below the noise at
// t_noise = tau ln(A/sigma) = 300. The trend test (see the header) passes where
// A exp(-s/tau) < 2.3 sigma sqrt(n_rest)/tau ~ 0.95 sigma here (n_rest ~ 1700 of 2000 samples), i.e.
// at s ~ t_noise, on a grid of candidates every 50 samples (over 300 seeds: 250 to 450). The window
// [t_noise - tau, t_noise + 2 tau] allows for that spread, while a detector that ignored the
// transient (0) or needed it to vanish far below the noise (> 500) fails.
TEST(SteadyState, RelaxationIsSteadyWhereTheTransientSinksIntoTheNoise) {
  const std::size_t n = 2000;
  const double tau = 100.0, amplitude = 1.0, sigma = 0.05;
  const double t_noise = tau * std::log(amplitude / sigma);
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    auto e = ar1_noise(n, 0.0, sigma, seed);
    const auto t = times(n, 1.0);
    for (std::size_t i = 0; i < n; ++i) e[i] += 10.0 + amplitude * std::exp(-t[i] / tau);
    const SteadyState s = detect_steady_state(t, e);
    ASSERT_TRUE(s.steady_from.has_value()) << s.reason;
    EXPECT_GE(*s.steady_from, t_noise - tau) << "seed " << seed;
    EXPECT_LE(*s.steady_from, t_noise + 2.0 * tau) << "seed " << seed;
  }
}

// E(t) grows like t^2 (a flow accelerating at a constant rate): by the last fifth it rises by ~30 %
// of its value across the window, far beyond correlated noise of 5 %: never steady.
TEST(SteadyState, AcceleratingFlowNeverConverges) {
  const std::size_t n = 1000;
  auto e = ar1_noise(n, 0.8, 0.05, 7);
  const auto t = times(n, 0.5);
  for (std::size_t i = 0; i < n; ++i) e[i] = (1.0 + t[i] / 100.0) * (1.0 + t[i] / 100.0) * (1.0 + e[i]);
  const SteadyState s = detect_steady_state(t, e);
  EXPECT_FALSE(s.steady_from.has_value()) << "steady from " << *s.steady_from;
  EXPECT_NE(s.reason.find("drifts"), std::string::npos) << s.reason;
  EXPECT_GT(s.trend_z, 3.0);
}

// Stationary AR(1) noise (correlation time 10 samples) about a constant: steady from the first
// sample. Both tests use block-averaged errors, so correlation is not mistaken for drift (over 300
// seeds no series was rejected at its first candidate; at most one rejected candidate, 2.5 % of the
// series, is allowed here).
TEST(SteadyState, StationarySeriesIsSteadyFromTheStart) {
  const std::size_t n = 3000;
  const auto t = times(n, 2.0);
  for (std::uint64_t seed : {11u, 12u, 13u, 14u}) {
    auto e = ar1_noise(n, 0.9, 0.2, seed);
    for (double& v : e) v += 5.0;
    const SteadyState s = detect_steady_state(t, e);
    ASSERT_TRUE(s.steady_from.has_value()) << s.reason;
    EXPECT_LE(*s.steady_from, 0.025 * n * 2.0 + 1e-9) << "seed " << seed;
  }
  // A noiseless constant series is steady from the start, too (zero errors, zero drift).
  const std::vector<double> flat(100, 3.0);
  EXPECT_EQ(detect_steady_state(times(100, 1.0), flat).steady_from, 0.0);
  // An elastic gas's kinetic energy: constant but for round-off (1e-13 relative), which has its own
  // "trend" many of its own standard errors long. Still steady from the start.
  std::vector<double> elastic(200);
  for (std::size_t i = 0; i < elastic.size(); ++i)
    elastic[i] = 3.0 * (1.0 + 1e-13 * static_cast<double>(i % 7) + 2e-14 * i);
  EXPECT_EQ(detect_steady_state(times(200, 1.0), elastic).steady_from, 0.0);
  // A real drift of 1e-6 over the series is still caught in a noiseless series.
  std::vector<double> creeping(200);
  for (std::size_t i = 0; i < creeping.size(); ++i) creeping[i] = 3.0 * (1.0 + 5e-9 * static_cast<double>(i));
  EXPECT_FALSE(detect_steady_state(times(200, 1.0), creeping).steady_from.has_value());
}

TEST(SteadyState, TooShortASeriesIsNotJudged) {
  const std::vector<double> e(20, 1.0);
  const SteadyState s = detect_steady_state(times(20, 1.0), e);
  EXPECT_FALSE(s.steady_from.has_value());
  EXPECT_TRUE(s.too_short);
  EXPECT_NE(s.reason.find("too few"), std::string::npos) << s.reason;
}
