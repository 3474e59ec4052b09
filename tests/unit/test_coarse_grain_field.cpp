// Coarse-grained fields (observe/coarse_grain_field.hpp): the kernels' closed forms, the fields
// integrating over the grid to the particle totals (mass, momentum, the contact virial) to round-off
// on periodic and walled boxes, a single particle's density against Lucy's normalized kernel, the
// kinetic stress of the fluctuations only (Galilean invariance), periodic images, and ranks' shares.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "grainflow/observe/coarse_grain_field.hpp"

namespace grainflow::observe {
namespace {

using Kind = CoarseGrainKernel::Kind;

PeriodicBox box_of(const Vec3& lo, const Vec3& hi, std::array<bool, 3> periodic) {
  PeriodicBox b;
  b.lo = lo;
  b.hi = hi;
  b.periodic = periodic;
  return b;
}

// Integral over the grid of cell values (kValues of them from `offset`) times the cell volume.
std::vector<double> integral(const CoarseGrainField& f, std::size_t offset, std::size_t count) {
  std::vector<double> out(count, 0.0);
  for (std::size_t k = 0; k < f.cell_count(); ++k)
    for (std::size_t m = 0; m < count; ++m) out[m] += f.cell_sums(k)[offset + m] * f.cell_volume();
  return out;
}

TEST(CoarseGrainKernel, LucyStandardDeviationIsCutoffOverRootTwelve) {
  // Each coordinate's variance (1/3) int r^4 phi dr / int r^2 phi dr by Simpson's rule on the
  // polynomial: exact to round-off at 2000 intervals.
  const CoarseGrainKernel lucy{Kind::lucy, 2.0};
  const int n = 2000;
  double r4 = 0.0, r2 = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double r = lucy.width * k / n;
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    r4 += w * r * r * r * r * lucy.shape(r * r);
    r2 += w * r * r * lucy.shape(r * r);
  }
  EXPECT_NEAR(std::sqrt(r4 / r2 / 3.0), lucy.standard_deviation(), 1e-12);
  EXPECT_DOUBLE_EQ(lucy.standard_deviation(), 2.0 / std::sqrt(12.0));
  // Over a disc (2D): (1/2) int r^3 phi dr / int r phi dr.
  CoarseGrainKernel disc = lucy;
  disc.dimension = 2;
  double q3 = 0.0, q1 = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double r = disc.width * k / n;
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 ? 4.0 : 2.0);
    q3 += w * r * r * r * disc.shape(r * r);
    q1 += w * r * disc.shape(r * r);
  }
  EXPECT_NEAR(std::sqrt(q3 / q1 / 2.0), disc.standard_deviation(), 1e-12);
  // Lucy's polynomial: 1 at the centre, 0 with zero slope at the cutoff; the Gaussian cut at 3 widths.
  EXPECT_DOUBLE_EQ(lucy.shape(0.0), 1.0);
  EXPECT_NEAR(lucy.shape(1.999 * 1.999), 0.0, 1e-8);
  EXPECT_EQ(lucy.shape(4.0), 0.0);
  const CoarseGrainKernel gauss{Kind::gaussian, 0.5};
  EXPECT_DOUBLE_EQ(gauss.shape(0.25), std::exp(-0.5) - std::exp(-4.5));  // shifted to end at zero
  EXPECT_NEAR(gauss.shape(1.4999 * 1.4999), 0.0, 1e-5);
  EXPECT_DOUBLE_EQ(gauss.reach(), 1.5);
  EXPECT_EQ(gauss.shape(1.5 * 1.5), 0.0);
}

// Random particles and contacts in a box periodic along x and z with walls along y: the fields'
// integrals are the totals, to round-off (each spread point's weights sum to one by construction;
// 1e-12 relative allows the sums over ~10^4 cells).
void expect_totals(CoarseGrainKernel kernel, std::array<int, 3> cells) {
  const PeriodicBox box = box_of({0, 0, 0}, {6, 10, 4}, {true, false, true});
  CoarseGrainField field(box, cells, kernel);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double mass = 0.0;
  Vec3 momentum;
  std::array<double, 9> virial{};
  std::vector<Vec3> x;
  for (int i = 0; i < 60; ++i) {
    const Vec3 xi{6 * u(rng), 0.5 + 9 * u(rng), 4 * u(rng)};
    const Vec3 v{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5};
    const double m = 0.5 + u(rng);
    field.add_particle(xi, m, 0.1, v);
    mass += m;
    momentum += m * v;
    x.push_back(xi);
  }
  // Contacts between neighbours in the list (partners at their image nearest i) and with the floor.
  for (std::size_t i = 1; i < x.size(); ++i) {
    Vec3 from = x[i - 1];
    for (int a : {0, 2}) from[a] += box.length(a) * std::round((x[i][a] - from[a]) / box.length(a));
    const Vec3 f{u(rng) - 0.5, u(rng), u(rng) - 0.5};
    if (i % 5 == 0) from = Vec3{x[i][0], 0.0, x[i][2]};  // a floor contact: from the contact point
    field.add_contact(x[i], from, f);
    const Vec3 b = x[i] - from;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) virial[3 * a + c] += b[a] * f[c];
  }
  field.close_sample();
  EXPECT_DOUBLE_EQ(field.lost_mass(), 0.0);
  EXPECT_NEAR(integral(field, CoarseGrainField::kMass, 1)[0], mass, 1e-12 * mass);
  const auto p = integral(field, CoarseGrainField::kMomentum, 3);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(p[a], momentum[a], 1e-12 * mass);
  const auto s = integral(field, CoarseGrainField::kContact, 9);
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(s[k], virial[k], 1e-12 * 60.0) << "component " << k;
}

TEST(CoarseGrainField, IntegratesToTheParticleTotals) {
  expect_totals({Kind::gaussian, 0.5}, {12, 20, 8});
  expect_totals({Kind::gaussian, 0.3}, {30, 50, 20});
  expect_totals({Kind::lucy, 1.5}, {12, 20, 8});
  // A kernel wider than the periodic box: every image is counted, the totals still hold.
  expect_totals({Kind::gaussian, 2.5}, {6, 10, 4});
}

TEST(CoarseGrainField, SingleParticleDensityIsLucysNormalizedKernel) {
  // Lucy's kernel in 3D is 105 / (16 pi c^3) (1 + 3q)(1 - q)^3; on cells c / 10 wide its sum over
  // the cells matches the integral to ~1e-6 (the kernel and its first two derivatives vanish at the
  // cutoff), so each cell holds m phi(r) to that.
  const double c = 1.0, h = 0.1, m = 2.0;
  const PeriodicBox box = box_of({0, 0, 0}, {4, 4, 4}, {false, false, false});
  const CoarseGrainKernel lucy{Kind::lucy, c};
  CoarseGrainField field(box, {40, 40, 40}, lucy);
  const Vec3 x{2.03, 1.96, 2.01};
  field.add_particle(x, m, 0.0, {});
  field.close_sample();
  const double norm = 105.0 / (16.0 * M_PI * c * c * c);
  double worst = 0.0;
  for (int iz = 0; iz < 40; ++iz)
    for (int iy = 0; iy < 40; ++iy)
      for (int ix = 0; ix < 40; ++ix) {
        const Vec3 centre{(ix + 0.5) * h, (iy + 0.5) * h, (iz + 0.5) * h};
        const double expected = m * norm * lucy.shape(norm2(centre - x));
        const std::size_t k = ix + 40 * (iy + 40 * iz);
        worst = std::max(worst, std::abs(coarse_grain_cell(field, k).density - expected));
      }
  EXPECT_LT(worst, 1e-5 * m * norm);
}

TEST(CoarseGrainField, DiscDensityIsLucysNormalizedKernelPerArea) {
  // In 2D Lucy's kernel is 5 / (pi c^2) (1 + 3q)(1 - q)^3 (its integral over the disc, 2 pi c^2
  // int q (1 + 3q)(1 - q)^3 dq = pi c^2 / 5), the density a mass per area over one cell along z;
  // on cells c / 10 wide to ~1e-5 as in 3D. A non-periodic z (the DEM engine's box for discs) is
  // still averaged over.
  const double c = 1.0, h = 0.1, m = 2.0;
  const PeriodicBox box = box_of({0, 0, 0}, {4, 4, 1}, {false, false, false});
  CoarseGrainKernel lucy{Kind::lucy, c};
  lucy.dimension = 2;
  CoarseGrainField field(box, {40, 40, 1}, lucy);
  EXPECT_TRUE(field.averaged(2));
  EXPECT_DOUBLE_EQ(field.cell_volume(), h * h);
  const Vec3 x{2.03, 1.96, 0.5};
  field.add_particle(x, m, 0.0, {});
  field.close_sample();
  const double norm = 5.0 / (M_PI * c * c);
  double worst = 0.0, mass = 0.0;
  for (int iy = 0; iy < 40; ++iy)
    for (int ix = 0; ix < 40; ++ix) {
      const Vec3 centre{(ix + 0.5) * h, (iy + 0.5) * h, 0.5};
      const double expected = m * norm * lucy.shape(norm2(centre - x));
      const double density = coarse_grain_cell(field, ix + 40 * iy).density;
      worst = std::max(worst, std::abs(density - expected));
      mass += density * h * h;
    }
  EXPECT_LT(worst, 1e-5 * m * norm);
  EXPECT_NEAR(mass, m, 1e-13 * m);
  EXPECT_THROW(CoarseGrainField(box, {40, 40, 2}, lucy), std::invalid_argument);
}

TEST(CoarseGrainField, KineticStressIsThatOfTheFluctuations) {
  // Two particles at the same place moving apart: the local mean velocity is U; the kinetic stress
  // sum m v'v' phi does not depend on U (Galilean invariance), the momentum density is rho U.
  const PeriodicBox box = box_of({0, 0, 0}, {2, 2, 2}, {true, true, true});
  auto stress_at = [&](const Vec3& U) {
    CoarseGrainField field(box, {8, 8, 8}, {Kind::gaussian, 0.4});
    field.add_particle({1, 1, 1}, 1.0, 0.0, Vec3{0.3, -0.1, 0.2} + U);
    field.add_particle({1, 1, 1}, 1.0, 0.0, Vec3{-0.3, 0.1, -0.2} + U);
    field.close_sample();
    return coarse_grain_cell(field, 4 + 8 * (4 + 8 * 4));
  };
  const CoarseGrainCell still = stress_at({}), moving = stress_at({5.0, -3.0, 2.0});
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(moving.kinetic[k], still.kinetic[k], 1e-12 * still.density) << k;
  // Each particle's sum m v v over the two is 2 m v0 v0: xx = 2 * 0.09 phi, xy = 2 * (-0.03) phi.
  const double phi = still.density / 2.0;
  EXPECT_NEAR(still.kinetic[0], 0.18 * phi, 1e-12 * phi);
  EXPECT_NEAR(still.kinetic[1], -0.06 * phi, 1e-12 * phi);
  EXPECT_NEAR(moving.velocity[0], 5.0, 1e-12);
  EXPECT_NEAR(moving.momentum[1], -3.0 * moving.density, 1e-12 * moving.density);
}

TEST(CoarseGrainField, PeriodicImagesAndRankSharesGiveTheSameField) {
  const PeriodicBox box = box_of({0, 0, 0}, {3, 3, 3}, {true, false, true});
  const CoarseGrainKernel kernel{Kind::gaussian, 0.4};
  CoarseGrainField one(box, {9, 9, 9}, kernel), image(box, {9, 9, 9}, kernel);
  CoarseGrainField rank0(box, {9, 9, 9}, kernel), rank1(box, {9, 9, 9}, kernel);
  const Vec3 a{0.1, 1.2, 2.9}, b{1.7, 1.0, 0.4};
  one.add_particle(a, 1.0, 0.5, {1, 0, 0});
  one.add_particle(b, 2.0, 0.5, {0, 1, 0});
  one.add_contact(a, b, {0.5, 0.2, 0.1});
  // The same particles given as images a box length away along x and z.
  image.add_particle(a + Vec3{3, 0, -3}, 1.0, 0.5, {1, 0, 0});
  image.add_particle(b + Vec3{-3, 0, 0}, 2.0, 0.5, {0, 1, 0});
  image.add_contact(a + Vec3{3, 0, -3}, b + Vec3{3, 0, -3}, {0.5, 0.2, 0.1});
  rank0.add_particle(a, 1.0, 0.5, {1, 0, 0});
  rank0.add_contact(a, b, {0.5, 0.2, 0.1});
  rank1.add_particle(b, 2.0, 0.5, {0, 1, 0});
  // Two ranks' shares added as the observer adds them (a reduction that adds rank 1's sums).
  RankReduce two_ranks;
  two_ranks.sum_in_place = [&](double* values, std::size_t count) {
    if (values != rank0.sums().data()) {  // the lost mass
      values[0] += rank1.lost_mass();
      return;
    }
    for (std::size_t k = 0; k < count; ++k) values[k] += rank1.sums()[k];
  };
  rank0.sum_over_ranks(two_ranks);
  for (std::size_t k = 0; k < one.sums().size(); ++k) {
    EXPECT_NEAR(image.sums()[k], one.sums()[k], 1e-12 * (1.0 + std::abs(one.sums()[k])));
    EXPECT_NEAR(rank0.sums()[k], one.sums()[k], 1e-12 * (1.0 + std::abs(one.sums()[k])));
  }
}

TEST(CoarseGrainField, APeriodicAxisOfOneCellIsAveragedOver) {
  // Profiles across a periodic slab: one cell along x and z, the kernel spreads along y only, so
  // where a particle lies along x and z does not matter, and the totals still hold.
  const PeriodicBox box = box_of({0, 0, 0}, {10, 6, 10}, {true, false, true});
  const CoarseGrainKernel kernel{Kind::gaussian, 0.5};
  CoarseGrainField a(box, {1, 12, 1}, kernel), b(box, {1, 12, 1}, kernel);
  a.add_particle({0.3, 2.2, 9.1}, 1.0, 0.5, {1, 0, 0});
  a.add_contact({0.3, 2.2, 9.1}, {0.3, 1.3, 9.5}, {0.1, 1.0, 0.0});
  b.add_particle({7.7, 2.2, 4.0}, 1.0, 0.5, {1, 0, 0});
  b.add_contact({7.7, 2.2, 4.0}, {7.7, 1.3, 4.4}, {0.1, 1.0, 0.0});
  for (std::size_t k = 0; k < a.sums().size(); ++k) EXPECT_NEAR(a.sums()[k], b.sums()[k], 1e-14);
  EXPECT_NEAR(integral(a, CoarseGrainField::kMass, 1)[0], 1.0, 1e-14);
  EXPECT_NEAR(integral(a, CoarseGrainField::kContact + 4, 1)[0], 0.9, 1e-14);  // b_y f_y
  // Along y the weights are the 1D (shifted) Gaussian's, normalized: cells at 2.25 and 2.75 around y = 2.2.
  const double near = a.cell_sums(4)[CoarseGrainField::kMass], next = a.cell_sums(5)[CoarseGrainField::kMass];
  EXPECT_NEAR(next / near, kernel.gaussian_factor(0.55 * 0.55) / kernel.gaussian_factor(0.05 * 0.05), 1e-12);
}

TEST(CoarseGrainField, MassBeyondTheBoxOnAWalledAxisIsCountedAsLost) {
  const PeriodicBox box = box_of({0, 0, 0}, {2, 2, 2}, {true, false, true});
  CoarseGrainField field(box, {4, 4, 4}, {Kind::gaussian, 0.2});
  field.add_particle({1, 3.0, 1}, 1.5, 0.0, {});   // 0.6 beyond the top: no cell centre within 3 widths
  field.add_particle({1, 2.05, 1}, 1.0, 0.0, {});  // just outside: still reaches the top cells
  EXPECT_DOUBLE_EQ(field.lost_mass(), 1.5);
  EXPECT_NEAR(integral(field, CoarseGrainField::kMass, 1)[0], 1.0, 1e-14);
}

}  // namespace
}  // namespace grainflow::observe
