// Bed height and bulk solids fraction (Lan 1994 section 4.2) on packings whose answers are known:
// a simple-cubic stack, the same stack with grains in ballistic flight above it, and a floor that
// is not at zero.
#include <gtest/gtest.h>

#include <cmath>

#include "grainflow/observe/bed_surface.hpp"

using namespace grainflow;
using namespace grainflow::observe;

namespace {

constexpr double kD = 0.003, kR = kD / 2;

void add(ParticleStore& p, Vec3 x) {
  const std::size_t i = p.size();
  p.resize(i + 1);
  p.position[i] = x;
  p.radius[i] = p.target_radius[i] = kR;
  p.mass[i] = 1.0;
  p.inv_mass[i] = 1.0;
  p.id[i] = static_cast<std::uint32_t>(i);
  p.motion[i] = Motion::free;
}

// n x n x layers simple-cubic spheres touching, the lowest layer resting on a floor at `floor`.
ParticleStore cubic_stack(int n, int layers, double floor) {
  ParticleStore p;
  for (int k = 0; k < layers; ++k)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) add(p, {(i + 0.5) * kD, floor + kR + k * kD, (j + 0.5) * kD});
  return p;
}

// Slices are d/10 = 0.2 r thick from the floor, so in these stacks the top layer's centres lie on a
// slice boundary. A slice [a r, b r] above the centres holds the slice-averaged cover
// (pi/4)(1 - (b^3 - a^3) / (3 (b - a))): 0.147 for [0.8, 1.0], above the default surface threshold
// 0.1, so the surface is read at the top of the spheres, height = layers * d.
double slice_cover(double a, double b) { return M_PI / 4.0 * (1.0 - (b * b * b - a * a * a) / (3.0 * (b - a))); }

}  // namespace

TEST(BedSurface, SimpleCubicStackHeightAndBulkFraction) {
  const int n = 5, layers = 6;
  const double area = (n * kD) * (n * kD);
  const auto p = cubic_stack(n, layers, 0.0);
  const BedSurface bed = measure_bed_surface(p, 3, 1, 0.0, area, kD, {});
  ASSERT_GT(slice_cover(0.8, 1.0), 0.1);
  EXPECT_NEAR(bed.height, layers * kD, 1e-9 * kD);
  EXPECT_EQ(bed.ballistic, 0);
  // Simple cubic packs pi/6 of the volume up to the spheres' tops.
  EXPECT_NEAR(bed.bulk_solids_fraction, M_PI / 6.0, 1e-9);
}

TEST(BedSurface, GrainsInFlightAboveAGapAreExcluded) {
  const int n = 5, layers = 4;
  const double area = (n * kD) * (n * kD);
  auto p = cubic_stack(n, layers, 0.0);
  // Three grains 3 to 6 diameters above the bed: the zones in between hold nothing.
  add(p, {0.5 * kD, layers * kD + 3.0 * kD, 0.5 * kD});
  add(p, {2.5 * kD, layers * kD + 4.5 * kD, 1.5 * kD});
  add(p, {3.5 * kD, layers * kD + 6.0 * kD, 3.5 * kD});
  const BedSurface bed = measure_bed_surface(p, 3, 1, 0.0, area, kD, {});
  EXPECT_EQ(bed.ballistic, 3);
  EXPECT_NEAR(bed.height, layers * kD, 1e-9 * kD);
  EXPECT_NEAR(bed.bulk_solids_fraction, M_PI / 6.0, 1e-9);
  // One grain resting in a hollow of the top layer (centre d / sqrt(2) above the layer's centres)
  // is part of the bed, but its slices cover at most pi/4/25 = 3% of the area, under the surface
  // threshold: it is neither ballistic nor raising the surface.
  auto q = cubic_stack(n, layers, 0.0);
  add(q, {kD, (layers - 1) * kD + kR + kD / std::sqrt(2.0), kD});
  const BedSurface resting = measure_bed_surface(q, 3, 1, 0.0, area, kD, {});
  EXPECT_EQ(resting.ballistic, 0);
  EXPECT_NEAR(resting.height, bed.height, 1e-12);
}

TEST(BedSurface, HeightIsMeasuredFromTheFloor) {
  const int n = 4, layers = 3;
  const double area = (n * kD) * (n * kD), floor = -0.0042;
  const auto p = cubic_stack(n, layers, floor);
  const BedSurface bed = measure_bed_surface(p, 3, 1, floor, area, kD, {});
  EXPECT_NEAR(bed.height, layers * kD, 1e-9 * kD);
}

TEST(BedSurface, ThresholdsMoveTheSurface) {
  // A higher surface threshold reads the surface lower in the top layer: at 0.5 the slice
  // [0.4 r, 0.6 r] still holds 0.586, the next [0.6 r, 0.8 r] only 0.398.
  const int n = 5, layers = 3;
  const double area = (n * kD) * (n * kD);
  const auto p = cubic_stack(n, layers, 0.0);
  BedSurfaceThresholds t;
  t.surface_fraction = 0.5;
  const BedSurface bed = measure_bed_surface(p, 3, 1, 0.0, area, kD, t);
  ASSERT_GT(slice_cover(0.4, 0.6), 0.5);
  ASSERT_LT(slice_cover(0.6, 0.8), 0.5);
  EXPECT_NEAR(bed.height, (layers - 1) * kD + 1.6 * kR, 1e-9 * kD);
}
