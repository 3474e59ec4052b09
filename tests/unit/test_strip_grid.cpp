// Strips across a shear flow (Campbell 1982, Fig. 2.11): exact disc–strip segment areas, the
// particle shares a strip grid hands out, and the branch-vector shares used for collisional stress.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "grainflow/analysis/strip_grid.hpp"

using namespace grainflow::observe;

namespace {
// Circular segment of height h (0 <= h <= 2r): r^2 acos((r - h) / r) - (r - h) sqrt(2 r h - h^2).
double segment_area(double r, double h) {
  return r * r * std::acos((r - h) / r) - (r - h) * std::sqrt(2.0 * r * h - h * h);
}
}  // namespace

TEST(DiscStripArea, MatchesCircularSegments) {
  const double r = 1.0, c = 3.0;
  for (double h : {0.0, 1e-6, 0.3, 1.0, 1.7, 2.0}) {
    EXPECT_NEAR(disc_strip_area(r, c, c + r - h, c + 10.0), segment_area(r, h), 1e-13) << h;  // top segment
    EXPECT_NEAR(disc_strip_area(r, c, c - 10.0, c - r + h), segment_area(r, h), 1e-13) << h;  // bottom segment
  }
  EXPECT_NEAR(disc_strip_area(r, c, c - 5.0, c + 5.0), M_PI, 1e-14);
  EXPECT_NEAR(disc_strip_area(r, c, c, c + 5.0), M_PI / 2.0, 1e-14);
  // A thin slice through the centre: its width times the diameter.
  EXPECT_NEAR(disc_strip_area(r, c, c - 1e-4, c + 1e-4), 2e-4 * 2.0 * r, 1e-11);
  EXPECT_EQ(disc_strip_area(r, c, c + r, c + 2.0), 0.0);
}

TEST(DiscStripArea, StripsPartitioningTheDiscSumToItsArea) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double r = 0.5 + u(rng), c = 10.0 * u(rng), thickness = (0.05 + 3.0 * u(rng)) * r;
    const StripGrid grid(2, 1, c - r - 2.0 * thickness * u(rng) - 1e-3, c + r + 2.0 * thickness, 200, 1.0);
    // Rebuild with the wanted thickness: count strips between lo and a hi far enough above.
    const int count = static_cast<int>(std::ceil((grid.hi() - grid.lo()) / thickness));
    const StripGrid strips(2, 1, grid.lo(), grid.lo() + count * thickness, count, 1.0);
    double area = 0.0, fraction = 0.0;
    strips.for_each_overlap(c, r, [&](int, double part, double share) {
      area += part;
      fraction += share;
    });
    EXPECT_NEAR(area, M_PI * r * r, 1e-12 * M_PI * r * r);
    EXPECT_NEAR(fraction, 1.0, 1e-12);
  }
}

TEST(StripGrid, SphereSharesSumToOneAndFollowMovingWalls) {
  StripGrid grid(3, 1, 0.0, 10.0, 5, 4.0);
  EXPECT_DOUBLE_EQ(grid.thickness(), 2.0);
  EXPECT_DOUBLE_EQ(grid.measure(), 8.0);
  double fraction = 0.0;
  grid.for_each_overlap(3.3, 1.0, [&](int k, double, double share) {
    EXPECT_TRUE(k == 1 || k == 2);
    fraction += share;
  });
  EXPECT_NEAR(fraction, 1.0, 1e-14);
  // A Couette cell's walls moved apart: the strips stretch, their count stays.
  grid.follow(-1.0, 11.0, 5.0);
  EXPECT_EQ(grid.count(), 5);
  EXPECT_DOUBLE_EQ(grid.thickness(), 2.4);
  EXPECT_EQ(grid.strip_of(-1.0), 0);
  EXPECT_EQ(grid.strip_of(10.999), 4);
  EXPECT_EQ(grid.strip_of(11.0), -1);
  EXPECT_EQ(grid.strip_of(-1.5), -1);
}

TEST(StripGrid, BranchVectorSharesAreLengthFractions) {
  const StripGrid grid(2, 1, 0.0, 10.0, 10, 3.0);
  double share[10] = {};
  grid.for_each_segment_part(2.5, 4.5, [&](int k, double f) { share[k] += f; });  // 0.5 + 1 + 0.5 of 2
  EXPECT_NEAR(share[2], 0.25, 1e-15);
  EXPECT_NEAR(share[3], 0.5, 1e-15);
  EXPECT_NEAR(share[4], 0.25, 1e-15);
  double in_order = 0.0, reversed = 0.0;
  grid.for_each_segment_part(7.2, 5.9, [&](int, double f) { reversed += f; });
  grid.for_each_segment_part(5.9, 7.2, [&](int, double f) { in_order += f; });
  EXPECT_NEAR(in_order, 1.0, 1e-14);
  EXPECT_NEAR(reversed, 1.0, 1e-14);
  int strip = -1;  // a branch vector along the flow: all of it in one strip
  grid.for_each_segment_part(6.3, 6.3, [&](int k, double f) {
    strip = k;
    EXPECT_EQ(f, 1.0);
  });
  EXPECT_EQ(strip, 6);
  double outside = 0.0;  // the part below the grid's bottom is nobody's
  grid.for_each_segment_part(-1.0, 1.0, [&](int, double f) { outside += f; });
  EXPECT_NEAR(outside, 0.5, 1e-15);
}

TEST(StripGrid, PeriodicSeamSplitsAParticleBetweenTheEndStrips) {
  // Strips spanning a periodic box [0, 10) in 5 strips of 2: a unit disc centred 0.3 above the seam
  // lies 0.7 below it, i.e. a bottom segment of height 0.7 belongs to the top strip (its image at
  // 10.3 reaches down to 9.3); the shares sum to the whole disc, as in the bulk. Without the period
  // that segment is lost.
  StripGrid grid(2, 1, 0.0, 10.0, 5, 1.0);
  grid.set_period(10.0);
  double top = 0.0, bottom = 0.0, total = 0.0;
  grid.for_each_overlap(0.3, 1.0, [&](int k, double part, double fraction) {
    (k == 4 ? top : bottom) += part;
    total += fraction;
    EXPECT_TRUE(k == 0 || k == 4) << k;
  });
  EXPECT_NEAR(top, segment_area(1.0, 0.7), 1e-13);
  EXPECT_NEAR(bottom, M_PI - segment_area(1.0, 0.7), 1e-13);
  EXPECT_NEAR(total, 1.0, 1e-14);
  // The same from above the seam: a sphere centred at 9.8 of radius 0.5 puts its top cap (height
  // 0.3) into strip 0.
  StripGrid spheres(3, 1, 0.0, 10.0, 5, 1.0);
  spheres.set_period(10.0);
  double cap = 0.0, sum = 0.0;
  spheres.for_each_overlap(9.8, 0.5, [&](int k, double part, double fraction) {
    if (k == 0) cap += part;
    sum += fraction;
  });
  EXPECT_NEAR(cap, M_PI * 0.3 * 0.3 * (3 * 0.5 - 0.3) / 3.0, 1e-14);  // spherical cap pi h^2 (3r - h) / 3
  EXPECT_NEAR(sum, 1.0, 1e-14);
  StripGrid open(2, 1, 0.0, 10.0, 5, 1.0);
  double open_total = 0.0;
  open.for_each_overlap(0.3, 1.0, [&](int, double, double fraction) { open_total += fraction; });
  EXPECT_NEAR(open_total, 1.0 - segment_area(1.0, 0.7) / M_PI, 1e-14);
}
