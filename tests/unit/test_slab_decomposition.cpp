// The slabs of an MPI run (dem/slab_decomposition.hpp): the axis across gravity, cuts that give each
// rank the same number of particles, owners and distances through a periodic face, and the cuts
// moving with the material.
#include <gtest/gtest.h>

#include <random>

#include "grainflow/dem/slab_decomposition.hpp"

namespace grainflow::dem {
namespace {

PeriodicBox box(double lx, double ly, double lz, bool periodic_x) {
  PeriodicBox b;
  b.lo = {0, 0, 0};
  b.hi = {lx, ly, lz};
  b.periodic = {periodic_x, false, true};
  return b;
}

TEST(SlabDecomposition, CutsAlongTheLongestAxisAcrossGravityAtQuantiles) {
  // Denser towards x = 0 (density 2 - x on [0, 1)): equal widths would not balance it.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x;
  while (x.size() < 40000) {
    const double a = u(rng), keep = u(rng);
    if (keep * 2.0 < 2.0 - a) x.push_back({a, 5.0 * u(rng), 0.5 * u(rng)});
  }
  // y is longest but carries gravity: x is the longest across it.
  const SlabDecomposition d = SlabDecomposition::balanced(x, box(1.0, 5.0, 0.5, true), {0, -9.81, 0}, 4, 0.01);
  EXPECT_EQ(d.axis, 0);
  std::vector<int> owned(4, 0);
  for (const Vec3& p : x) ++owned[d.owner(p)];
  for (int r = 0; r < 4; ++r) EXPECT_NEAR(owned[r], 10000, 2) << "rank " << r;  // quantile cuts: exact but for ties
  // The first cut of density 2 - x lies where x (4 - x) / 3 = 1/4 of the mass: x = 2 - sqrt(3.25).
  EXPECT_NEAR(d.bounds[1], 2.0 - std::sqrt(3.25), 0.01);  // 1 % of a 40,000-sample quantile
}

TEST(SlabDecomposition, OwnersAndDistancesThroughThePeriodicFace) {
  SlabDecomposition d;
  d.axis = 0;
  d.bounds = {0.0, 0.25, 0.5, 1.0};
  d.periodic = true;
  EXPECT_EQ(d.owner({-0.1, 0, 0}), 2);  // wraps to 0.9
  EXPECT_EQ(d.owner({1.2, 0, 0}), 0);   // wraps to 0.2
  EXPECT_EQ(d.owner({0.25, 0, 0}), 1);  // a cut belongs to the slab above it
  EXPECT_NEAR(d.distance_to({0.98, 0, 0}, 0), 0.02, 1e-12);  // across the face
  EXPECT_NEAR(d.distance_to({0.3, 0, 0}, 0), 0.05, 1e-12);
  EXPECT_EQ(d.distance_to({0.3, 0, 0}, 1), 0.0);
  d.periodic = false;  // walls: the end slabs reach beyond the box, nothing wraps
  EXPECT_EQ(d.owner({-0.1, 0, 0}), 0);
  EXPECT_EQ(d.owner({1.2, 0, 0}), 2);
  EXPECT_NEAR(d.distance_to({0.98, 0, 0}, 0), 0.73, 1e-12);
  EXPECT_EQ(d.distance_to({1.5, 0, 0}, 2), 0.0);
}

TEST(SlabDecomposition, RebalancingMovesTheCutsWithTheMaterial) {
  SlabDecomposition d;
  d.axis = 0;
  d.bounds = {0.0, 0.5, 1.0};
  // All the material has gathered in [0.6, 0.8): the cut moves to its middle, 0.7.
  std::vector<double> counts(100, 0.0);
  for (int b = 60; b < 80; ++b) counts[b] = 10.0;
  d.rebalance(counts);
  EXPECT_NEAR(d.bounds[1], 0.7, 1e-12);
  EXPECT_EQ(d.bounds.front(), 0.0);
  EXPECT_EQ(d.bounds.back(), 1.0);
  EXPECT_EQ(d.bin_of({0.705, 0, 0}, 100), 70);
}

}  // namespace
}  // namespace grainflow::dem
