// Flyvbjerg-Petersen block averaging (src/grainflow/analysis/block_average.hpp): the standard
// error of the mean of an AR(1) series against its exact value, white noise against the naive
// error, the levels' bookkeeping, and the fallback when the series is too short. Fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include "grainflow/analysis/block_average.hpp"

using namespace grainflow::analysis;

namespace {

// Stationary AR(1): x_{i+1} = phi x_i + sigma sqrt(1 - phi^2) xi, marginal variance sigma^2,
// correlation phi^k. The variance of its mean over n samples tends to
// sigma^2 / n * (1 + phi) / (1 - phi) (corrections O(1/(n (1 - phi)))).
std::vector<double> ar1(std::size_t n, double phi, double sigma, double mean, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  std::vector<double> x(n);
  double v = sigma * g(rng);
  const double kick = sigma * std::sqrt(1.0 - phi * phi);
  for (double& s : x) {
    s = mean + v;
    v = phi * v + kick * g(rng);
  }
  return x;
}

}  // namespace

// n = 2^18. The plateau estimate has the statistical error ds of its level (1-3% here) and a low
// bias from correlations that outlast the blocks, ~ tau/b relative (1-2% at the levels chosen);
// over 300 seeds the estimator gave ratios 0.983 +- 0.028 (phi = 0.9) and 0.991 +- 0.013
// (phi = 0.5) to the exact value. A 10% tolerance is the bias plus over 3 of those spreads, and
// still catches the naive error (4.4 and 1.7 times too small) or a wrong level.
TEST(AnalysisBlockAverage, Ar1PlateauMatchesTheExactStandardError) {
  const std::size_t n = 1 << 18;
  const double sigma = 2.0;
  for (double phi : {0.5, 0.9}) {
    const std::vector<double> x = ar1(n, phi, sigma, 10.0, phi == 0.5 ? 31 : 32);
    const BlockAverage b = block_average(x);
    const double exact = sigma / std::sqrt(static_cast<double>(n)) * std::sqrt((1.0 + phi) / (1.0 - phi));
    std::printf("[ blocking ] phi %.1f: plateau level %zu (block %zu): %.5g +- %.2g, exact %.5g, naive %.5g\n", phi,
                b.plateau_level, b.levels[b.plateau_level].block_size, b.standard_error, b.standard_error_error, exact,
                b.naive_standard_error);
    EXPECT_TRUE(b.plateau_found) << phi;
    EXPECT_NEAR(b.standard_error, exact, 0.10 * exact) << phi;
    // The naive error is sigma / sqrt(n) to within its own 1/sqrt(2n) = 0.14% (5 sigma: 0.7%);
    // it underestimates by the factor sqrt((1 + phi)/(1 - phi)).
    EXPECT_NEAR(b.naive_standard_error, sigma / std::sqrt(static_cast<double>(n)),
                0.007 * sigma / std::sqrt(static_cast<double>(n)));
    // The mean is the arithmetic mean; the true mean 10 is within 4 exact standard errors.
    EXPECT_NEAR(b.mean, std::accumulate(x.begin(), x.end(), 0.0) / static_cast<double>(n), 1e-12);
    EXPECT_NEAR(b.mean, 10.0, 4.0 * exact);
  }
}

// White noise: the blocks are uncorrelated at every level, so the plateau value is the naive
// error within the plateau level's own uncertainty (3 of them: the two estimates share data, so
// their difference is smaller than either error).
TEST(AnalysisBlockAverage, WhiteNoisePlateauIsTheNaiveError) {
  const std::size_t n = 100'000;  // not a power of two: odd tails are dropped along the way
  const std::vector<double> x = ar1(n, 0.0, 1.5, -3.0, 33);
  const BlockAverage b = block_average(x);
  std::printf("[ blocking ] white noise: plateau level %zu: %.5g +- %.2g, naive %.5g\n", b.plateau_level,
              b.standard_error, b.standard_error_error, b.naive_standard_error);
  EXPECT_TRUE(b.plateau_found);
  EXPECT_NEAR(b.standard_error, b.naive_standard_error, 3.0 * b.standard_error_error);
  // Each candidate level fails one of its two agreements by chance with probability ~2%: a plateau
  // beyond level 3 would mean the criterion rejects agreeing levels.
  EXPECT_LE(b.plateau_level, 3u);

  // Bookkeeping: block sizes double, counts halve (rounded down), while at least 2 blocks remain;
  // each level's uncertainty is s / sqrt(2 (n' - 1)); level 0 is the sample standard deviation
  // over sqrt(n).
  std::size_t blocks = n;
  for (std::size_t l = 0; l < b.levels.size(); ++l) {
    EXPECT_EQ(b.levels[l].block_size, std::size_t{1} << l);
    EXPECT_EQ(b.levels[l].blocks, blocks);
    EXPECT_DOUBLE_EQ(b.levels[l].standard_error_error,
                     b.levels[l].standard_error / std::sqrt(2.0 * (static_cast<double>(blocks) - 1.0)));
    blocks /= 2;
  }
  EXPECT_EQ(b.levels.back().blocks, 3u);  // 100000 -> ... -> 6 -> 3 -> (1: not a level)
  double ss = 0.0;
  for (double v : x) ss += (v - b.mean) * (v - b.mean);
  EXPECT_NEAR(b.naive_standard_error, std::sqrt(ss / (n - 1.0) / n), 1e-12 * b.naive_standard_error);
}

// A series much shorter than needed (phi = 0.999: correlation time ~2000 samples, n = 4096) has
// no plateau among the levels with >= 16 blocks; the largest of them (block 256) is returned, and
// it is a lower bound: below the exact error, which is 45 times the naive one.
TEST(AnalysisBlockAverage, TooShortSeriesFallsBackToTheLargestLevel) {
  const std::size_t n = 4096;
  const double phi = 0.999;
  const std::vector<double> x = ar1(n, phi, 1.0, 0.0, 34);
  const BlockAverage b = block_average(x);
  const double exact = 1.0 / std::sqrt(static_cast<double>(n)) * std::sqrt((1.0 + phi) / (1.0 - phi));
  EXPECT_FALSE(b.plateau_found);
  EXPECT_EQ(b.plateau_level, 8u);
  EXPECT_EQ(b.levels[b.plateau_level].blocks, 16u);
  EXPECT_LT(b.standard_error, exact);
  EXPECT_GT(b.standard_error, 3.0 * b.naive_standard_error);
  EXPECT_THROW(block_average(std::vector<double>{1.0}), std::invalid_argument);
}
