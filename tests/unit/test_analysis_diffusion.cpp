// Self-diffusion estimators (src/grainflow/analysis/diffusion.hpp): the velocity-autocorrelation
// integral and the mean-square-displacement slope (Lan 1994 eqs. 3-2-5, 3-3-5, 4-4-2, 4-4-5) on
// synthetic processes with known D, and the Savage-Dai formula (eqs. 4-3-3, 4-3-4) against the
// analytic column of Lan's Table 4.5. Fixed seeds; every tolerance is a stated number of standard
// errors or a round-off bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "grainflow/analysis/correlation.hpp"
#include "grainflow/analysis/diffusion.hpp"

using namespace grainflow::analysis;

namespace {

// Ensemble sizes: the figures below in optimised builds; a quarter of the particles in
// unoptimised ones (the Debug preset with AddressSanitizer runs ~20 times slower). The tolerances
// are multiples of standard errors that scale as 1/sqrt(particles), so they follow automatically.
#ifdef NDEBUG
constexpr std::size_t kParticleScale = 4;
#else
constexpr std::size_t kParticleScale = 1;
#endif

struct MeanAndError {
  double mean = 0.0, standard_error = 0.0;
};

// Mean of independent per-particle estimates and its standard error, sd / sqrt(N).
MeanAndError mean_and_error(const std::vector<double>& values) {
  const double n = static_cast<double>(values.size());
  double sum = 0.0, sum2 = 0.0;
  for (double v : values) {
    sum += v;
    sum2 += v * v;
  }
  const double mean = sum / n;
  return {mean, std::sqrt((sum2 / n - mean * mean) / (n - 1.0))};
}

// N independent Ornstein-Uhlenbeck velocities, stationary from the first sample, by the exact AR(1)
// update v_{i+1} = phi v_i + sigma sqrt(1 - phi^2) xi, phi = exp(-dt/tau): C(t) = sigma^2 e^{-t/tau}.
// Positions integrate the sampled velocity, x_{i+1} = x_i + v_i dt.
struct OuEnsemble {
  std::vector<std::vector<double>> velocity, position;
};

OuEnsemble ornstein_uhlenbeck(std::size_t particles, std::size_t samples, double sigma, double tau, double dt,
                              std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  const double phi = std::exp(-dt / tau), kick = sigma * std::sqrt(1.0 - phi * phi);
  OuEnsemble e;
  e.velocity.assign(particles, std::vector<double>(samples));
  e.position.assign(particles, std::vector<double>(samples));
  for (std::size_t p = 0; p < particles; ++p) {
    double v = sigma * g(rng), x = 0.0;
    for (std::size_t i = 0; i < samples; ++i) {
      e.velocity[p][i] = v;
      e.position[p][i] = x;
      x += v * dt;
      v = phi * v + kick * g(rng);
    }
  }
  return e;
}

}  // namespace

// sigma = 1 m/s, tau = 1 s, dt = 0.1 s: D = sigma^2 tau = 1 m^2/s. Sampled at dt, the trapezoid
// integral of C(k) = sigma^2 phi^k is sigma^2 dt (1 + phi) / (2 (1 - phi)) = D (h/2) coth(h/2) with
// h = dt/tau, i.e. D (1 + h^2/12) = 1.000833: that is the exact target, and the long-time MSD slope
// of the integrated positions, dt^2 sigma^2 (1 + phi)/(1 - phi) per lag, gives the same value.
//
// Expected errors. VACF integral to K lags: by Bartlett's formula the covariances of C(k) sum to
// Var(sum_k C(k)) ~ (K + 1) S^2 / (N n), S = sum over all lags of C = 2 D / dt, so the relative
// standard error is 2 sqrt((K + 1) / (N n)): 0.99% for K = 100, n = 4096, N = 1000 (2.0% at
// N = 250). The MSD slope over lags [K/2, K] with K = 400: ~1.7% at N = 1000 (the spread of the
// per-particle fits, 55%: about twice the relative error sqrt(2K/(3n)) = 26% of MSD(K) itself,
// Qian, Sheetz & Elson 1991, because the slope is a difference of MSD values). Both are linear in
// the per-particle data, so the ensemble estimate is exactly the mean of the per-particle ones:
// their spread is an honest standard error. Tolerance: 4 standard errors (false alarm 6e-5).
TEST(AnalysisDiffusion, OrnsteinUhlenbeckFromVacfIntegralAndMsdSlope) {
  const double sigma = 1.0, tau = 1.0, dt = 0.1;
  const std::size_t particles = 250 * kParticleScale, samples = 4096, vacf_lags = 100, msd_lags = 400;
  const OuEnsemble e = ornstein_uhlenbeck(particles, samples, sigma, tau, dt, 11);
  const double phi = std::exp(-dt / tau);
  const double expected = sigma * sigma * dt * (1.0 + phi) / (2.0 * (1.0 - phi));
  ASSERT_NEAR(expected, sigma * sigma * tau * (1.0 + dt * dt / 12.0), 1e-6);

  const std::vector<double> vacf = autocorrelation(e.velocity, vacf_lags);
  const VacfIntegral integral = diffusion_from_vacf(vacf, dt);
  const std::vector<double> msd = mean_square_displacement(e.position, msd_lags);
  const MsdFit fit = diffusion_from_msd(msd, dt);
  EXPECT_EQ(fit.first_lag, msd_lags / 2);
  EXPECT_EQ(fit.last_lag, msd_lags);

  std::vector<double> per_particle_vacf, per_particle_msd, per_particle_intercept;
  for (std::size_t p = 0; p < particles; ++p) {
    per_particle_vacf.push_back(diffusion_from_vacf(autocorrelation(e.velocity[p], vacf_lags), dt).coefficient);
    const MsdFit own = diffusion_from_msd(mean_square_displacement(e.position[p], msd_lags), dt);
    per_particle_msd.push_back(own.coefficient);
    per_particle_intercept.push_back(own.intercept);
  }
  const MeanAndError from_vacf = mean_and_error(per_particle_vacf), from_msd = mean_and_error(per_particle_msd);
  const MeanAndError intercept = mean_and_error(per_particle_intercept);
  // Pooling is linear: the ensemble estimate is the mean of the particles' (to round-off).
  EXPECT_NEAR(integral.coefficient, from_vacf.mean, 1e-12);
  EXPECT_NEAR(fit.coefficient, from_msd.mean, 1e-12);

  const double vacf_error_theory = 2.0 * std::sqrt((vacf_lags + 1.0) / (particles * static_cast<double>(samples)));
  std::printf("[ OU       ] D true %.5f | VACF %.5f +- %.5f (theory +- %.5f) | MSD %.5f +- %.5f m^2/s, N = %zu\n",
              expected, integral.coefficient, from_vacf.standard_error, vacf_error_theory * expected, fit.coefficient,
              from_msd.standard_error, particles);
  EXPECT_NEAR(integral.coefficient, expected, 4.0 * from_vacf.standard_error);
  EXPECT_NEAR(fit.coefficient, expected, 4.0 * from_msd.standard_error);
  // The error model itself: the measured spread is an estimate of the theory's value good to
  // 1/sqrt(2N) = 4.5% at N = 250; a factor 1.3 either way is > 6 of those.
  EXPECT_GT(from_vacf.standard_error, vacf_error_theory * expected / 1.3);
  EXPECT_LT(from_vacf.standard_error, vacf_error_theory * expected * 1.3);

  // The running integral follows D (1 - e^{-t/tau}) (trapezoid factor aside): at t = tau it has
  // 63% of D, by 10 tau the plateau (e^{-10} = 5e-5 left). The statistical error of I(k) is at most
  // that of the full integral, so 4 of those bound the comparison.
  ASSERT_EQ(integral.running_integral.size(), vacf_lags + 1);
  EXPECT_EQ(integral.running_integral[0], 0.0);
  EXPECT_NEAR(integral.running_integral[10], expected * (1.0 - std::exp(-1.0)), 4.0 * from_vacf.standard_error);
  EXPECT_NEAR(integral.running_integral[50], expected * (1.0 - std::exp(-5.0)), 4.0 * from_vacf.standard_error);
  EXPECT_DOUBLE_EQ(integral.running_integral.back(), integral.coefficient);

  // The MSD fit's intercept: MSD(t) -> 2 D (t - tau) for an OU process, so -2 D tau = -2 m^2
  // (the discrete sampling shifts it by O(dt^2)); 4 standard errors of the per-particle intercepts.
  EXPECT_NEAR(fit.intercept, intercept.mean, 1e-10);
  EXPECT_NEAR(fit.intercept, -2.0 * expected * tau, 4.0 * intercept.standard_error);
  // Three components of the same process: the total of eq. (4-4-2) is their mean, and the MSD of
  // |r|^2 (three components summed) with dimensions = 3 gives the same D (eq. 3-3-5).
  const double components[] = {integral.coefficient, integral.coefficient, integral.coefficient};
  EXPECT_DOUBLE_EQ(total_diffusion(components), integral.coefficient);
  std::vector<double> msd_r(msd.size());
  for (std::size_t k = 0; k < msd.size(); ++k) msd_r[k] = 3.0 * msd[k];
  EXPECT_NEAR(diffusion_from_msd(msd_r, dt, 3).coefficient, fit.coefficient, 1e-12);
}

// A lattice random walk of +-s steps every dt: MSD(k) = k s^2 exactly in expectation, so
// D = s^2 / (2 dt) with no bias at any lag. s = 0.01 m, dt = 1 ms: D = 0.05 m^2/s. Expected error
// of the slope over lags [100, 200] from n = 2000 steps: the per-walker fits scatter by ~56%
// (about twice the sqrt(2K/(3n)) = 26% relative error of MSD(K) itself, Qian et al. 1991), i.e.
// 2.8% for 400 walkers (5.6% for 100). The standard error used is that measured spread
// (the estimate is linear in the walkers' MSDs, as above); 4 standard errors.
TEST(AnalysisDiffusion, RandomWalkFromMsdSlope) {
  const double step = 0.01, dt = 0.001, expected = step * step / (2.0 * dt);
  const std::size_t walkers = 100 * kParticleScale, samples = 2000, max_lag = 200;
  std::mt19937_64 rng(12);
  std::bernoulli_distribution coin(0.5);
  std::vector<std::vector<double>> position(walkers, std::vector<double>(samples));
  for (auto& path : position) {
    double x = 5.0;  // anywhere: the MSD is translation invariant
    for (double& p : path) {
      p = x;
      x += coin(rng) ? step : -step;
    }
  }
  const MsdFit fit = diffusion_from_msd(mean_square_displacement(position, max_lag), dt);
  std::vector<double> per_walker, per_walker_intercept;
  for (const auto& path : position) {
    const MsdFit own = diffusion_from_msd(mean_square_displacement(path, max_lag), dt);
    per_walker.push_back(own.coefficient);
    per_walker_intercept.push_back(own.intercept);
  }
  const MeanAndError spread = mean_and_error(per_walker), intercept = mean_and_error(per_walker_intercept);
  std::printf("[ walk     ] D true %.5f | MSD %.5f +- %.5f m^2/s (%zu walkers)\n", expected, fit.coefficient,
              spread.standard_error, walkers);
  EXPECT_NEAR(fit.coefficient, spread.mean, 1e-12);
  EXPECT_NEAR(fit.coefficient, expected, 4.0 * spread.standard_error);
  EXPECT_NEAR(fit.intercept, 0.0, 4.0 * intercept.standard_error);  // MSD = k s^2 passes through 0

  // A window given explicitly; D of an exact straight line is exact.
  std::vector<double> line(51);
  for (std::size_t k = 0; k < line.size(); ++k) line[k] = 0.3 + 2.0 * 0.04 * static_cast<double>(k) * dt;
  const MsdFit exact = diffusion_from_msd(line, dt, 10, 40);
  EXPECT_NEAR(exact.coefficient, 0.04, 1e-12);
  EXPECT_NEAR(exact.intercept, 0.3, 1e-12);
  EXPECT_THROW(diffusion_from_msd(line, dt, 40, 10), std::invalid_argument);
  EXPECT_THROW(diffusion_from_msd(line, dt, 10, 51), std::invalid_argument);
}

// Lan Table 4.5 ("Analytical" column): d = 0.1 m, e = 0.9 (Table 4.4), the table's bulk solids
// fraction and cell-average temperature (m^2/s^2). The formula as printed reproduces both values;
// the tolerance is half a unit in the last printed digit.
TEST(AnalysisDiffusion, SavageDaiReproducesLanTable45) {
  const double d = 0.1, e = 0.9;
  EXPECT_NEAR(savage_dai_diffusion(d, 0.7950, e, 0.44), 0.00532, 0.000005);  // Gamma = 90 g
  EXPECT_NEAR(savage_dai_diffusion(d, 13.80, e, 0.14), 0.2116, 0.00005);     // Gamma = 483 g
  // Carnahan-Starling at contact: 1 in the dilute limit, (2 - nu) / (2 (1 - nu)^3).
  EXPECT_DOUBLE_EQ(carnahan_starling_g0(0.0), 1.0);
  EXPECT_NEAR(carnahan_starling_g0(0.44), 1.56 / (2.0 * 0.56 * 0.56 * 0.56), 1e-14);
  // Scalings: D ~ sqrt(T), ~ d, ~ 1/(1 + e).
  EXPECT_NEAR(savage_dai_diffusion(d, 4.0 * 0.7950, e, 0.44), 2.0 * savage_dai_diffusion(d, 0.7950, e, 0.44), 1e-15);
  EXPECT_NEAR(savage_dai_diffusion(0.2, 0.7950, 0.0, 0.44), 2.0 * 1.9 * savage_dai_diffusion(d, 0.7950, e, 0.44),
              1e-15);
  EXPECT_THROW(savage_dai_diffusion(d, 1.0, e, 1.0), std::invalid_argument);
  EXPECT_THROW(savage_dai_diffusion(d, -1.0, e, 0.3), std::invalid_argument);
}
