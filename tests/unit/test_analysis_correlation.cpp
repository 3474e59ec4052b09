// Correlation functions and the mean-square displacement (src/grainflow/analysis/correlation.hpp,
// Lan 1994 eqs. 3-2-2b, 3-2-3, 3-2-6, 3-3-7): the FFT estimators against the direct O(n^2) sums
// they replace, over the full lag range where zero padding matters; recovery of known integer and
// fractional delays; the RealFft round trip underneath.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "grainflow/analysis/correlation.hpp"
#include "grainflow/analysis/fft.hpp"

using namespace grainflow::analysis;

namespace {

std::vector<double> gaussian_series(std::size_t n, double mean, std::mt19937_64& rng) {
  std::normal_distribution<double> g(mean, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = g(rng);
  return x;
}

// The definitions, summed directly.
double direct_cross(const std::vector<double>& x, const std::vector<double>& y, long k) {
  const long n = static_cast<long>(x.size());
  double sum = 0.0;
  for (long i = 0; i < n; ++i)
    if (i + k >= 0 && i + k < n) sum += x[i] * y[i + k];
  return sum / static_cast<double>(n - std::labs(k));
}

double direct_msd(const std::vector<double>& x, std::size_t k) {
  double sum = 0.0;
  for (std::size_t i = 0; i + k < x.size(); ++i) sum += (x[i + k] - x[i]) * (x[i + k] - x[i]);
  return sum / static_cast<double>(x.size() - k);
}

double sum_of_squares(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return s;
}

// Round-off bound for the FFT route. The raw lag sum sum_i x_i x_{i+k} comes out of a forward and
// an inverse transform of length m with an absolute error of order eps log2(m) sum_i x_i^2
// (FFT error grows like log m; eps = 2.2e-16, log2 m <= 12 here: ~3e-15 sum x^2); dividing by
// n - k gives the bound below with a factor ~30 to spare. For k <= n/2 it is <= 2e-13 C(0)-scale,
// i.e. the ~1e-12 relative agreement asked of the FFT route.
double fft_tolerance(double squares, std::size_t n, std::size_t k) {
  return 1e-13 * squares / static_cast<double>(n - k);
}

// A stationary smooth signal that can be evaluated at any real t: white noise w_j on the integers
// convolved with a Gaussian of width s. Its autocorrelation is a Gaussian of width s sqrt(2), so a
// copy delayed by a fractional number of samples has a known cross-correlation peak.
double smooth_signal(const std::vector<double>& w, double t, double s) {
  const long lo = std::max(0L, static_cast<long>(std::floor(t - 7.0 * s)));
  const long hi = std::min(static_cast<long>(w.size()) - 1, static_cast<long>(std::ceil(t + 7.0 * s)));
  double sum = 0.0;
  for (long j = lo; j <= hi; ++j) {
    const double u = (t - static_cast<double>(j)) / s;
    sum += w[j] * std::exp(-0.5 * u * u);
  }
  return sum;
}

}  // namespace

TEST(AnalysisRealFft, RoundTripAndKnownTransform) {
  std::mt19937_64 rng(1);
  for (std::size_t n : {1u, 2u, 7u, 64u, 1000u, 1001u}) {
    RealFft fft(n);
    ASSERT_EQ(fft.spectrum_size(), n / 2 + 1);
    const std::vector<double> x = gaussian_series(n, 0.5, rng);
    std::vector<std::complex<double>> spectrum(fft.spectrum_size());
    std::vector<double> back(n);
    fft.forward(x, spectrum);
    fft.inverse(spectrum, back);
    // FFTW's inverse is unnormalised: n x, to a round-off of a few eps log2(n) |x|.
    for (std::size_t j = 0; j < n; ++j) EXPECT_NEAR(back[j], static_cast<double>(n) * x[j], 1e-12 * n) << n << ' ' << j;
  }
  // A cosine of 3 cycles in 16 samples has its whole spectrum in bin 3: X_3 = n/2.
  RealFft fft(16);
  std::vector<double> c(16);
  for (std::size_t j = 0; j < 16; ++j) c[j] = std::cos(2.0 * M_PI * 3.0 * j / 16.0);
  std::vector<std::complex<double>> spectrum(fft.spectrum_size());
  fft.forward(c, spectrum);
  for (std::size_t k = 0; k < spectrum.size(); ++k) EXPECT_NEAR(std::abs(spectrum[k]), k == 3 ? 8.0 : 0.0, 1e-13) << k;
  // Shorter input is zero padded; moved-from objects release nothing twice.
  RealFft moved = std::move(fft);
  moved.forward(std::vector<double>{1.0}, spectrum);
  for (const auto& z : spectrum) EXPECT_NEAR(std::abs(z - 1.0), 0.0, 1e-15);
  EXPECT_EQ(good_fft_size(1), 1u);
  EXPECT_EQ(good_fft_size(11), 12u);
  EXPECT_EQ(good_fft_size(1025), 1029u);  // 3 * 7^3
}

TEST(AnalysisAutocorrelation, FftEqualsDirectSumOverAllLags) {
  std::mt19937_64 rng(2);
  const std::size_t n = 1000;
  // A non-zero mean makes wrap-around visible at every lag if the padding were too short.
  const std::vector<double> x = gaussian_series(n, 3.0, rng);
  const double squares = sum_of_squares(x);
  const std::vector<double> c = autocorrelation(x, n - 1);
  ASSERT_EQ(c.size(), n);
  for (std::size_t k = 0; k < n; ++k)
    EXPECT_NEAR(c[k], direct_cross(x, x, static_cast<long>(k)), fft_tolerance(squares, n, k)) << k;

  // Autocovariance: the series' mean removed first.
  double mean = 0.0;
  for (double v : x) mean += v / n;
  std::vector<double> centred(x);
  for (double& v : centred) v -= mean;
  const std::vector<double> cov = autocorrelation(x, 300, true);
  for (std::size_t k = 0; k <= 300; ++k)
    EXPECT_NEAR(cov[k], direct_cross(centred, centred, static_cast<long>(k)), fft_tolerance(squares, n, k)) << k;
}

TEST(AnalysisAutocorrelation, EnsembleWeightsEveryProductAlike) {
  std::mt19937_64 rng(3);
  const std::vector<std::vector<double>> series = {gaussian_series(500, 1.0, rng), gaussian_series(731, -0.5, rng),
                                                   gaussian_series(64, 2.0, rng)};
  const std::size_t max_lag = 63;
  const std::vector<double> c = autocorrelation(series, max_lag);
  double squares = 0.0;
  for (const auto& s : series) squares += sum_of_squares(s);
  for (std::size_t k = 0; k <= max_lag; ++k) {
    double products = 0.0, count = 0.0;
    for (const auto& s : series) {
      products += direct_cross(s, s, static_cast<long>(k)) * static_cast<double>(s.size() - k);
      count += static_cast<double>(s.size() - k);
    }
    EXPECT_NEAR(c[k], products / count, 1e-13 * squares / count) << k;
  }
  // Equal lengths: the plain mean of the per-series functions (eq. 3-2-6).
  const std::vector<std::vector<double>> equal = {series[0], gaussian_series(500, 0.0, rng)};
  const auto pooled = autocorrelation(equal, 100), a = autocorrelation(equal[0], 100),
             b = autocorrelation(equal[1], 100);
  for (std::size_t k = 0; k <= 100; ++k)
    EXPECT_NEAR(pooled[k], 0.5 * (a[k] + b[k]), 1e-13 * (std::fabs(a[0]) + std::fabs(b[0])));
  EXPECT_THROW(autocorrelation(series, 64), std::invalid_argument);  // the third series is too short
}

TEST(AnalysisCrossCorrelation, FftEqualsDirectSumAtPositiveAndNegativeLags) {
  std::mt19937_64 rng(4);
  const std::size_t n = 777, max_lag = n - 1;
  const std::vector<double> x = gaussian_series(n, 1.5, rng), y = gaussian_series(n, -2.0, rng);
  const std::vector<double> c = cross_correlation(x, y, max_lag);
  ASSERT_EQ(c.size(), 2 * max_lag + 1);
  const double scale = std::sqrt(sum_of_squares(x) * sum_of_squares(y));
  for (long k = -static_cast<long>(max_lag); k <= static_cast<long>(max_lag); ++k)
    EXPECT_NEAR(c[max_lag + k], direct_cross(x, y, k), fft_tolerance(scale, n, std::labs(k))) << k;
}

// White noise and a copy delayed by d samples: C_xy(k) = 1 at k = d and O(1/sqrt(n)) elsewhere.
// The parabolic refinement moves the lag by (C(d-1) - C(d+1)) / 4 at most, with C(d +- 1) pure
// noise of standard deviation 1/sqrt(n) = 0.016: a shift of std 0.006 samples; 0.05 is 9 sigma.
TEST(AnalysisCrossCorrelation, RecoversIntegerDelaysOfEitherSign) {
  std::mt19937_64 rng(5);
  const std::size_t n = 4096;
  const std::vector<double> noise = gaussian_series(n + 100, 0.0, rng);
  for (long delay : {37L, -23L, 0L}) {
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = noise[i + 50];
      y[i] = noise[static_cast<std::size_t>(static_cast<long>(i) + 50 - delay)];  // y(t) = x(t - delay)
    }
    const std::vector<double> c = cross_correlation(x, y, 60);
    EXPECT_NEAR(lag_of_maximum(c), static_cast<double>(delay), 0.05) << delay;
  }
}

// A smooth signal (Gaussian-filtered noise, width s = 4 samples) and a copy delayed by 12.3
// samples, sampled exactly. The expected cross-correlation is R(k - 12.3), R a Gaussian of width
// sigma = s sqrt(2). The parabola through the three samples around a Gaussian peak is biased by a
// known amount (computed below: -0.0015 samples); the sampling noise of the peak position is
// ~0.0012 samples (its spread over 20 seeds for this n). 0.01 samples covers both with margin and
// still fails if the refinement is missing (error 0.3) or mis-signed (error 0.6).
TEST(AnalysisCrossCorrelation, RecoversFractionalDelayAndWaveSpeed) {
  std::mt19937_64 rng(6);
  const double s = 4.0, delay = 12.3, dt = 0.002;
  const std::size_t n = 1 << 15;
  const std::vector<double> w = gaussian_series(n + 200, 0.0, rng);
  std::vector<double> x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = smooth_signal(w, static_cast<double>(i) + 100.0, s);
    y[i] = smooth_signal(w, static_cast<double>(i) + 100.0 - delay, s);
  }
  const double lag = lag_of_maximum(cross_correlation(x, y, 40, true));

  const double width = s * std::sqrt(2.0), f = delay - 12.0;
  auto r = [&](double t) { return std::exp(-t * t / (2.0 * width * width)); };
  const double left = r(-1.0 - f), mid = r(-f), right = r(1.0 - f);
  const double parabolic = 12.0 + 0.5 * (left - right) / (left - 2.0 * mid + right);
  EXPECT_NEAR(parabolic, delay, 0.003);  // the bias itself is small for a peak this wide
  EXPECT_NEAR(lag, parabolic, 0.01);
  EXPECT_NEAR(lag, delay, 0.01);

  // A zone 0.25 m above the floor, responding 12.3 samples of 2 ms later: 0.25 / 0.0246 m/s.
  EXPECT_NEAR(propagation_speed(0.25, lag * dt), 0.25 / (delay * dt), 0.01 / delay * 0.25 / (delay * dt));
  EXPECT_TRUE(std::isnan(propagation_speed(0.25, 0.0)));
  EXPECT_TRUE(std::isnan(propagation_speed(0.25, -1.0)));
}

TEST(AnalysisCrossCorrelation, PeakAtTheEndsIsNotRefined) {
  EXPECT_DOUBLE_EQ(lag_of_maximum(std::vector<double>{3.0, 1.0, 0.5, 0.2, 0.1}), -2.0);
  EXPECT_DOUBLE_EQ(lag_of_maximum(std::vector<double>{0.0, 1.0, 0.5, 0.2, 4.0}), 2.0);
  // A symmetric peak stays on its sample; a parabola's vertex is found exactly.
  EXPECT_DOUBLE_EQ(lag_of_maximum(std::vector<double>{0.0, 1.0, 2.0, 1.0, 0.0}), 0.0);
  auto parabola = [](double k) { return 5.0 - (k - 0.3) * (k - 0.3); };
  EXPECT_NEAR(lag_of_maximum(std::vector<double>{parabola(-2), parabola(-1), parabola(0), parabola(1), parabola(2)}),
              0.3, 1e-14);
  EXPECT_THROW(lag_of_maximum(std::vector<double>{1.0, 2.0}), std::invalid_argument);
}

// Positions far from the origin (1000 + a random walk of unit steps), the case in which S1 - 2 S2
// cancels most. The mean subtracted first leaves terms of size sum (x - mean)^2, the scale of the
// round-off bound (same argument as fft_tolerance); the MSD itself is of order k.
TEST(AnalysisMeanSquareDisplacement, FftEqualsDirectSum) {
  std::mt19937_64 rng(7);
  const std::size_t n = 2000;
  std::vector<double> x(n);
  const std::vector<double> steps = gaussian_series(n, 0.0, rng);
  double pos = 1000.0;
  for (std::size_t i = 0; i < n; ++i) x[i] = pos += steps[i];
  double mean = 0.0;
  for (double v : x) mean += v / n;
  double spread = 0.0;
  for (double v : x) spread += (v - mean) * (v - mean);

  const std::size_t max_lag = n - 1;
  const std::vector<double> msd = mean_square_displacement(x, max_lag);
  ASSERT_EQ(msd.size(), n);
  EXPECT_EQ(msd[0], 0.0);
  for (std::size_t k = 1; k <= max_lag; ++k)
    EXPECT_NEAR(msd[k], direct_msd(x, k), 4.0 * fft_tolerance(spread, n, k)) << k;

  // Ensemble of unequal lengths: every displacement weighted alike.
  std::vector<double> other(1200);
  for (std::size_t i = 0; i < other.size(); ++i) other[i] = -50.0 + 0.3 * steps[i] * static_cast<double>(i % 7);
  const std::vector<std::vector<double>> both = {x, other};
  const std::vector<double> pooled = mean_square_displacement(both, 500);
  for (std::size_t k = 1; k <= 500; ++k) {
    const double a = direct_msd(x, k) * static_cast<double>(n - k),
                 b = direct_msd(other, k) * static_cast<double>(other.size() - k);
    EXPECT_NEAR(pooled[k], (a + b) / static_cast<double>(n + other.size() - 2 * k), 4e-13 * spread / (n - k)) << k;
  }
  EXPECT_THROW(mean_square_displacement(other, 1200), std::invalid_argument);
}
