// Welch power spectral density (src/grainflow/analysis/spectrum.hpp, Welch 1967; Lan 1994 eq. 3-2-1
// and section 4.3): the peak of a sampled sinusoid in noise, Parseval (exactly for one segment,
// statistically for many), and the level of white noise in x^2/Hz. Fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include "grainflow/analysis/spectrum.hpp"

using namespace grainflow::analysis;

namespace {

double sample_variance(const std::vector<double>& x) {
  const double n = static_cast<double>(x.size());
  const double mean = std::accumulate(x.begin(), x.end(), 0.0) / n;
  double s = 0.0;
  for (double v : x) s += (v - mean) * (v - mean);
  return s / n;
}

double integral(const PowerSpectrum& s) {
  return std::accumulate(s.density.begin(), s.density.end(), 0.0) * s.resolution;
}

// A zone velocity like Lan's section 4.3: amplitude A at the floor's 7 Hz plus white noise of
// standard deviation sigma_n, sampled at 200 Hz.
std::vector<double> sinusoid_in_noise(std::size_t n, double dt, double frequency, double amplitude, double noise,
                                      std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, noise);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i)
    x[i] = 0.3 + amplitude * std::sin(2.0 * M_PI * frequency * static_cast<double>(i) * dt + 0.4) + g(rng);
  return x;
}

}  // namespace

// Segments of 1024 samples at 200 Hz: bins 0.195 Hz wide; 7 Hz lies between bins 35 and 36
// (35.84 bins), so the largest density must sit on one of them: within one bin of 7 Hz. The
// sinusoid's peak density, A^2/2 spread over the Hann window's ~1.5-bin noise bandwidth, is
// ~ 2 / (1.5 * 0.195) = 7 (m/s)^2/Hz against the noise floor 2 sigma_n^2 dt = 0.01: no noise bin
// can compete.
TEST(AnalysisWelchPsd, SinusoidInNoisePeaksAtItsFrequency) {
  const double dt = 1.0 / 200.0, f0 = 7.0;
  const std::size_t n = 1 << 15, segment = 1024;
  const std::vector<double> x = sinusoid_in_noise(n, dt, f0, 2.0, 1.0, 21);
  const PowerSpectrum s = welch_psd(x, dt, segment);
  ASSERT_EQ(s.frequency.size(), segment / 2 + 1);
  ASSERT_EQ(s.density.size(), segment / 2 + 1);
  EXPECT_DOUBLE_EQ(s.resolution, 200.0 / 1024.0);
  EXPECT_DOUBLE_EQ(s.frequency[36], 36.0 * 200.0 / 1024.0);
  EXPECT_DOUBLE_EQ(s.frequency.back(), 100.0);  // Nyquist
  EXPECT_EQ(s.segments, (n - segment) / (segment / 2) + 1);
  EXPECT_LE(std::fabs(peak_frequency(s) - f0), s.resolution);
  std::printf("[ PSD      ] peak at %.4f Hz for a 7 Hz sinusoid (bin width %.4f Hz)\n", peak_frequency(s),
              s.resolution);

  // Parseval over many segments. The integral is the window-weighted mean square of the
  // mean-removed segments: the same samples as the plain variance, weighted alike except in the
  // first and last half segment (3% of the data) and less the per-segment mean (a relative 1/L of
  // the noise power). The difference is a few 1e-3 of the variance; 1% bounds it. Against the
  // exact variance A^2/2 + sigma_n^2 = 3 the sample variance of the noise adds its own error,
  // sigma_n^2 sqrt(2/n) = 0.008, i.e. 0.26% of 3: 1.5% is over 5 of those plus the 1%.
  const double variance = sample_variance(x);
  std::printf("[ PSD      ] integral %.5f, sample variance %.5f, exact 3\n", integral(s), variance);
  EXPECT_NEAR(integral(s), variance, 0.01 * variance);
  EXPECT_NEAR(integral(s), 3.0, 0.015 * 3.0);
}

// One segment covering the whole series: the integral must equal sum w^2 (x - mean)^2 / sum w^2 to
// round-off (Parseval for the DFT; FFT error ~ eps log2 L relative, 1e-12 leaves a factor ~100).
// Odd and even lengths exercise the unpaired Nyquist bin.
TEST(AnalysisWelchPsd, ParsevalIsExactForOneSegment) {
  std::mt19937_64 rng(22);
  std::normal_distribution<double> g(1.0, 2.0);
  for (std::size_t n : {256u, 257u, 1000u}) {
    std::vector<double> x(n);
    for (double& v : x) v = g(rng);
    const double mean = std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(n);
    double weighted = 0.0, weights = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      const double w = std::pow(std::sin(M_PI * static_cast<double>(j) / static_cast<double>(n)), 2);
      weighted += w * w * (x[j] - mean) * (x[j] - mean);
      weights += w * w;
    }
    const PowerSpectrum s = welch_psd(x, 0.01, n);
    EXPECT_EQ(s.segments, 1u);
    EXPECT_NEAR(integral(s), weighted / weights, 1e-12 * weighted / weights) << n;
  }
}

// White noise of variance sigma^2 sampled every dt has the flat one-sided density 2 sigma^2 dt.
// Averaged over 254 bins (2 .. 255) of 127 segments, the estimate's relative error is about
// 1/sqrt(254 * 127 * 0.5) = 0.4% (overlapping Hann segments are ~half as many independent ones);
// the mean removal lowers the first two bins only, which are left out. Tolerance 2%, 5 sigma.
TEST(AnalysisWelchPsd, WhiteNoiseLevelIsTwoSigmaSquaredDt) {
  const double dt = 0.004, sigma = 0.5;
  const std::size_t n = 1 << 15, segment = 512;
  std::mt19937_64 rng(23);
  std::normal_distribution<double> g(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = g(rng);
  const PowerSpectrum s = welch_psd(x, dt, segment);
  double level = 0.0;
  for (std::size_t k = 2; k + 1 < s.density.size(); ++k) level += s.density[k];
  level /= static_cast<double>(s.density.size() - 3);
  std::printf("[ PSD      ] white-noise level %.6g, expected %.6g (x^2/Hz)\n", level, 2.0 * sigma * sigma * dt);
  EXPECT_NEAR(level, 2.0 * sigma * sigma * dt, 0.02 * 2.0 * sigma * sigma * dt);
  EXPECT_THROW(welch_psd(x, dt, n + 1), std::invalid_argument);
  EXPECT_THROW(welch_psd(x, 0.0, 64), std::invalid_argument);
}
