// Campbell's pair distributions (analysis/pair_distribution.hpp, Campbell 1982 section 3.4.3):
// an ideal gas (independent uniform positions) must give the number density at every distance,
// within Poisson error, in a walled cell narrow enough that the slices reach past the walls, in 3D,
// and in a periodic box; an elastic hard-disc gas run with the event-driven engine must show the
// excluded core, the contact peak at 2R and the bulk density at large distance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "elastic_disc_gas.hpp"
#include "grainflow/analysis/pair_distribution.hpp"

using namespace grainflow;
using namespace grainflow::analysis;

namespace {

// N points placed independently and uniformly in a cell [0, W) x [0, gap) (x [0, D) in 3D), each
// sample afresh. R = 1.
StateSamples ideal_gas(int dimension, std::size_t samples, std::size_t particles, double width, double gap,
                       double depth, bool periodic_y, unsigned seed) {
  StateSamples s;
  s.dimension = dimension;
  s.samples = samples;
  s.particles = particles;
  s.radius.assign(particles, 1.0);
  s.box_depth = depth;
  s.period_y = periodic_y ? gap : 0.0;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  s.position.resize(samples * particles * 3);
  s.velocity.assign(s.position.size(), 0.0);
  s.angular_velocity.assign(s.position.size(), 0.0);
  for (std::size_t t = 0; t < samples; ++t) {
    for (std::size_t i = 0; i < particles; ++i) {
      double* x = &s.position[(t * particles + i) * 3];
      // Unwrapped coordinates along the periodic axes: any image must count the same.
      x[0] = width * (uniform(rng) + std::floor(5.0 * uniform(rng)) - 2.0);
      x[1] = gap * (uniform(rng) + (periodic_y ? std::floor(3.0 * uniform(rng)) - 1.0 : 0.0));
      x[2] = dimension == 3 ? depth * (uniform(rng) + std::floor(3.0 * uniform(rng)) - 1.0) : 0.0;
    }
    s.wall_lo.push_back(0.0);
    s.wall_hi.push_back(gap);
    s.strip_lo.push_back(0.0);
    s.strip_hi.push_back(gap);
    s.box_width.push_back(width);
  }
  return s;
}

// Each of the N - 1 other particles is uniform over the cell, independently of the test particle,
// so the pair density is exactly (N - 1) / V (the reported n = N / V exceeds it by 1/N). The
// samples are independent, so the block-averaged error is a sound standard error: |z| < 5 in every
// slice (a false alarm below 1e-4 over the 150 slices of a test).
void expect_ideal(const std::vector<double>& n, const std::vector<double>& error, double expected, const char* label) {
  int slices = 0;
  for (std::size_t k = 0; k < n.size(); ++k) {
    if (std::isnan(n[k])) continue;
    ++slices;
    EXPECT_NEAR(n[k], expected, 5.0 * error[k]) << label << " slice " << k;
    EXPECT_LT(error[k], 0.05 * expected) << label;  // enough counts for the test to mean something
  }
  EXPECT_GT(slices, 0) << label;
}

}  // namespace

TEST(PairDistributions, IdealGasInANarrowWalledCellGivesTheNumberDensityAtEveryDistance) {
  // Gap 14 R: the test band (within 2R of y = 7R) and the 8R of slices reach past both walls, so
  // the clipped measures matter. Width 12 R: the forward distances cover [0, 8R) fully, the
  // nearest-image ones only up to W/2 = 6R (the slices beyond are empty: NaN).
  const double width = 12.0, gap = 14.0;
  const StateSamples s = ideal_gas(2, 1500, 200, width, gap, 1.0, false, 3);
  const PairDistributions p = pair_distributions(s, {});
  ASSERT_EQ(p.r.size(), 50u);
  EXPECT_NEAR(p.r.back(), 8.0 - 0.08, 1e-12);
  const double expected = (200.0 - 1.0) / (width * gap);
  EXPECT_NEAR(p.number_density, 200.0 / (width * gap), 1e-12);
  // A fraction 4/14 of the particles lie in the band: binomial s.d. of the mean over 1500 samples.
  EXPECT_NEAR(p.test_particles_per_sample, 200.0 * 4.0 / 14.0,
              4.0 * std::sqrt(200.0 * 4.0 / 14.0 * 10.0 / 14.0 / 1500.0));
  expect_ideal(p.normal, p.normal_error, expected, "normal");
  expect_ideal(p.parallel, p.parallel_error, expected, "parallel");
  expect_ideal(p.parallel_two_sided, p.parallel_two_sided_error, expected, "two-sided");
  for (std::size_t k = 0; k < p.r.size(); ++k) EXPECT_EQ(std::isnan(p.parallel_two_sided[k]), p.r[k] > 6.0) << k;
}

TEST(PairDistributions, IdealGasIn3DGivesTheNumberDensity) {
  const double width = 20.0, gap = 24.0, depth = 10.0;
  const StateSamples s = ideal_gas(3, 400, 400, width, gap, depth, false, 4);
  const PairDistributions p = pair_distributions(s, {});
  const double expected = (400.0 - 1.0) / (width * gap * depth);
  expect_ideal(p.normal, p.normal_error, expected, "normal");
  expect_ideal(p.parallel, p.parallel_error, expected, "parallel");
  expect_ideal(p.parallel_two_sided, p.parallel_two_sided_error, expected, "two-sided");
}

TEST(PairDistributions, IdealGasIn3DBetweenZWallsClipsTheTube) {
  // z bounded by walls 5R apart: the parallel tube (|dz| < 2R) is cut by them for most test particles.
  const double width = 16.0, gap = 24.0, depth = 5.0;
  StateSamples s = ideal_gas(3, 600, 300, width, gap, depth, false, 6);
  s.periodic_z = false;
  for (std::size_t k = 0; k < s.samples * s.particles; ++k)  // back into the box: no z images now
    s.position[3 * k + 2] -= depth * std::floor(s.position[3 * k + 2] / depth);
  const PairDistributions p = pair_distributions(s, {});
  const double expected = (300.0 - 1.0) / (width * gap * depth);
  expect_ideal(p.normal, p.normal_error, expected, "normal");
  expect_ideal(p.parallel, p.parallel_error, expected, "parallel");
  expect_ideal(p.parallel_two_sided, p.parallel_two_sided_error, expected, "two-sided");
}

TEST(PairDistributions, IdealGasInAPeriodicBoxUsesEveryParticle) {
  const double width = 20.0, length = 20.0;
  const StateSamples s = ideal_gas(2, 300, 150, width, length, 1.0, true, 5);
  const PairDistributions p = pair_distributions(s, {});
  EXPECT_DOUBLE_EQ(p.test_particles_per_sample, 150.0);
  const double expected = (150.0 - 1.0) / (width * length);
  expect_ideal(p.normal, p.normal_error, expected, "normal");
  expect_ideal(p.parallel, p.parallel_error, expected, "parallel");
  expect_ideal(p.parallel_two_sided, p.parallel_two_sided_error, expected, "two-sided");
}

TEST(PairDistributions, ElasticDiscGasShowsTheContactPeakAndTheBulkDensity) {
  // 100 elastic rough discs at nu = 0.3 in a periodic square of 32.4 R (elastic_disc_gas.hpp),
  // 2000 samples: every disc is a test particle.
  const StateSamples s = test::elastic_disc_gas_samples(2000);
  const PairDistributions p = pair_distributions(s, {});
  const double length = test::gas_box_length(), n = 100.0 / (length * length);
  EXPECT_NEAR(p.number_density, n, 1e-12 * n);
  EXPECT_NEAR(p.number_density * M_PI, test::kGasFraction, 1e-9);
  auto mean_over = [&](const std::vector<double>& f, double from, double to) {
    double sum = 0.0;
    int count = 0;
    for (std::size_t k = 0; k < p.r.size(); ++k)
      if (p.r[k] > from && p.r[k] < to) sum += f[k], ++count;
    return sum / count;
  };
  std::size_t peak = 0;
  for (std::size_t k = 0; k < p.r.size(); ++k)
    if (p.parallel[k] > p.parallel[peak]) peak = k;
  std::printf(
      "  gas: n = %.5f; parallel peak %.4f at r = %.2f; normal at 6-8 R %.5f, parallel %.5f; normal at r = 2R %.5f\n",
      n, p.parallel[peak], p.r[peak], mean_over(p.normal, 6.0, 8.0), mean_over(p.parallel, 6.0, 8.0),
      mean_over(p.normal, 1.9, 2.1));
  // Far away (6R-8R, three to four diameters) the density is the bulk one: hard-disc structure at
  // nu = 0.3 has decayed to well below 1 % there, and a closed box of N discs shifts the far density
  // by O(1/N) = 1 %; statistical errors of these means are ~0.1 % (normal) and ~0.3 % (parallel),
  // a few times more with the correlation of successive samples. Tolerance 2 %.
  EXPECT_NEAR(mean_over(p.normal, 6.0, 8.0), n, 0.02 * n);
  EXPECT_NEAR(mean_over(p.parallel, 6.0, 8.0), n, 0.02 * n);
  // The contact peak of the parallel distribution (particles in the test particle's layer) lies at
  // 2R, in the slice holding it or a neighbour, well above n: the hard-disc g is ~1.8 at contact
  // (Henderson) and the layer's slice averages it over |dy| < 2R (measured: 1.39 n; a slice's
  // Poisson error is ~1 %).
  EXPECT_NEAR(p.r[peak], 2.0, 0.25);
  EXPECT_GT(p.parallel[peak], 1.25 * n);
  // Excluded core: a layer partner within R along the flow must sit at |dy| in (sqrt(4 - dx^2), 2)
  // R, under 13.4 % of the layer; even at the contact density that holds < 0.25 n.
  EXPECT_LT(mean_over(p.parallel, 0.0, 1.0), 0.25 * n);
  // Across the flow, n [1 + (1/W) integral (g - 1) dx] along a line at |dy| from the test disc: at
  // |dy| ~ 0 the line crosses the whole excluded disc, -4R / W = -12 % (a little less with the
  // contact shell's crossings: measured 0.90 n); at |dy| = 2R it grazes the contact shell (+3-4 %).
  std::size_t normal_peak = 0;
  for (std::size_t k = 0; k < p.r.size(); ++k)
    if (p.r[k] < 4.0 && p.normal[k] > p.normal[normal_peak]) normal_peak = k;
  EXPECT_LT(mean_over(p.normal, 0.0, 0.5), 0.95 * n);
  EXPECT_NEAR(p.r[normal_peak], 2.0, 0.4);
  EXPECT_GT(p.normal[normal_peak], 1.02 * n);
}
