// The grid of sub-domains of an MPI run (dem/domain_decomposition.hpp): the grid's shape from the
// rank count and the material's shape (the least cut area; a thin bed is cut across gravity only, a
// cube in three axes), cuts that give each slice of the grid the same number of particles, owners,
// distances and neighbours through periodic faces, and the cuts moving with the material.
#include <gtest/gtest.h>

#include <random>

#include "grainflow/dem/domain_decomposition.hpp"

namespace grainflow::dem {
namespace {

using Shape = std::array<int, 3>;

PeriodicBox box(double lx, double ly, double lz, std::array<bool, 3> periodic) {
  PeriodicBox b;
  b.lo = {0, 0, 0};
  b.hi = {lx, ly, lz};
  b.periodic = periodic;
  return b;
}

TEST(DomainDecomposition, TheShapeHasTheLeastCutArea) {
  const double w = 0.01;  // ghost width; sub-domains at least 2 w thick where cut
  // A bed 1 x 1 wide, 0.1 deep along gravity (y), periodic sideways: never cut along its depth.
  // Periodic slabs and columns cut the same area (each slice has two faces); the fewer cut axes win.
  EXPECT_EQ(DomainDecomposition::choose_shape(2, {1, 0.1, 1}, {true, false, true}, 2 * w, 1), (Shape{2, 1, 1}));
  EXPECT_EQ(DomainDecomposition::choose_shape(4, {1, 0.1, 1}, {true, false, true}, 2 * w, 1), (Shape{4, 1, 1}));
  // Walls on the sides: 4 slabs cut 3 planes, 2 x 2 columns only 2.
  EXPECT_EQ(DomainDecomposition::choose_shape(4, {1, 0.1, 1}, {false, false, false}, 2 * w, 1), (Shape{2, 1, 2}));
  // A walled cube: 2 x 2 x 2 (3 planes) against 2 x 4 columns (4) and 8 slabs (7). Periodic, 2 x 2 x 2
  // and 2 x 4 cut the same area (6 planes), and the fewer cut axes win; 64 ranks go 4 x 4 x 4
  // (12 planes, against 14 for 2 x 4 x 8 and 16 for 8 x 8).
  EXPECT_EQ(DomainDecomposition::choose_shape(8, {1, 1, 1}, {false, false, false}, 2 * w, -1), (Shape{2, 2, 2}));
  EXPECT_EQ(DomainDecomposition::choose_shape(8, {1, 1, 1}, {true, true, true}, 2 * w, -1), (Shape{4, 2, 1}));
  EXPECT_EQ(DomainDecomposition::choose_shape(64, {1, 1, 1}, {true, true, true}, 2 * w, -1), (Shape{4, 4, 4}));
  // A chute 1 long (x), 0.1 deep (y, gravity), 0.2 wide (z): slabs along the flow.
  EXPECT_EQ(DomainDecomposition::choose_shape(6, {1, 0.1, 0.2}, {true, false, true}, 2 * w, 1), (Shape{6, 1, 1}));
  // Primes have one axis to go on: the one with the smallest cross-section (x before z on a tie).
  EXPECT_EQ(DomainDecomposition::choose_shape(7, {0.3, 0.3, 1}, {true, true, true}, 2 * w, -1), (Shape{1, 1, 7}));
  EXPECT_EQ(DomainDecomposition::choose_shape(5, {1, 0.2, 0.3}, {true, false, true}, 2 * w, 1), (Shape{5, 1, 1}));
  // Slabs thinner than two ghost layers come last: 0.3 / 16 < 0.02, so 16 ranks go 4 x 4 on the base.
  EXPECT_EQ(DomainDecomposition::choose_shape(16, {0.3, 0.05, 0.3}, {true, false, true}, 2 * w, 1), (Shape{4, 1, 4}));
  // Gravity's axis stays uncut even where cutting it would cut less (a bed poured from a height
  // spans the box at first), unless the others would be too thin: a silo 0.05 wide and 2 tall.
  EXPECT_EQ(DomainDecomposition::choose_shape(4, {0.3, 1.0, 0.3}, {false, false, false}, 2 * w, 1), (Shape{2, 1, 2}));
  EXPECT_EQ(DomainDecomposition::choose_shape(8, {0.05, 2.0, 0.05}, {false, false, false}, 2 * w, 1), (Shape{1, 8, 1}));
}

TEST(DomainDecomposition, CutsAtQuantilesGiveEachRankItsShare) {
  // Denser towards x = 0 (density 2 - x on [0, 1)) in a wide, thin bed: equal widths would not
  // balance it, and the cuts along x follow the density while those along z are even.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> x;
  while (x.size() < 40000) {
    const double a = u(rng), keep = u(rng);
    if (keep * 2.0 < 2.0 - a) x.push_back({a, 0.05 * u(rng), u(rng)});
  }
  const DomainDecomposition d =
      DomainDecomposition::balanced(x, box(1.0, 0.5, 1.0, {false, false, false}), {0, -9.81, 0}, 4, 0.01);
  ASSERT_EQ(d.shape, (Shape{2, 1, 2}));  // walls on the sides: columns (2 cut planes) beat slabs (3)
  std::vector<int> owned(4, 0);
  for (const Vec3& p : x) ++owned[d.owner(p)];
  // Marginal quantiles: each column gets a quarter only to the sampling noise of its share of
  // 40,000 uniform-in-z points, sqrt(10000 * 3/4) ~ 90; 4 sigma.
  for (int r = 0; r < 4; ++r) EXPECT_NEAR(owned[r], 10000, 350) << "rank " << r;
  // The x cut of density 2 - x lies where x (4 - x) / 3 = 1/2 of the mass: x = 2 - sqrt(2.5).
  EXPECT_NEAR(d.bounds[0][1], 2.0 - std::sqrt(2.5), 0.01);  // 1 % of a 40,000-sample quantile
  EXPECT_NEAR(d.bounds[2][1], 0.5, 0.01);
  EXPECT_EQ(d.bounds[1], (std::vector<double>{0.0, 0.5}));  // gravity's axis is not cut
}

TEST(DomainDecomposition, OwnersAndDistancesThroughPeriodicFaces) {
  DomainDecomposition d;
  d.shape = {3, 1, 2};
  d.bounds = {std::vector<double>{0.0, 0.25, 0.5, 1.0}, std::vector<double>{0.0, 1.0},
              std::vector<double>{0.0, 0.5, 1.0}};
  d.periodic = {true, false, true};
  EXPECT_EQ(d.rank_at({2, 0, 1}), 5);
  EXPECT_EQ(d.coordinates(5), (Shape{2, 0, 1}));
  EXPECT_EQ(d.owner({-0.1, 0.5, 0.2}), 2);  // x wraps to 0.9
  EXPECT_EQ(d.owner({1.2, 0.5, 0.7}), 3);   // x wraps to 0.2, z in the upper half
  EXPECT_EQ(d.owner({0.25, 0.5, 0.5}), 4);  // a cut belongs to the slice above it
  EXPECT_EQ(d.owner({0.3, 7.0, 0.1}), 1);   // an uncut axis is the whole line
  // Distances: across the periodic face in x; corners are Euclidean.
  EXPECT_NEAR(d.distance_to({0.98, 0.5, 0.2}, 0), 0.02, 1e-12);
  EXPECT_NEAR(d.distance_to({0.3, 0.5, 0.2}, 0), 0.05, 1e-12);
  EXPECT_NEAR(d.distance_to({0.3, 0.5, 0.53}, 0), std::hypot(0.05, 0.03), 1e-12);
  EXPECT_NEAR(d.distance_to({0.3, 0.5, 0.98}, 0), std::hypot(0.05, 0.02), 1e-12);  // z wraps: 0.02 from it
  EXPECT_EQ(d.distance_to({0.3, 0.5, 0.2}, 1), 0.0);
  EXPECT_NEAR(d.lower(4).x, 0.25, 0);
  EXPECT_NEAR(d.upper(4).z, 1.0, 0);
  d.periodic = {false, false, false};  // walls: the end slices reach beyond the box, nothing wraps
  EXPECT_EQ(d.owner({-0.1, 0.5, 0.2}), 0);
  EXPECT_EQ(d.owner({1.2, 0.5, 1.3}), 5);
  EXPECT_NEAR(d.distance_to({0.98, 0.5, 0.2}, 0), 0.73, 1e-12);
  EXPECT_EQ(d.distance_to({1.5, 0.5, 1.5}, 5), 0.0);
}

TEST(DomainDecomposition, NeighboursAreTheRanksWithinReach) {
  DomainDecomposition d;
  d.shape = {2, 1, 2};
  d.bounds = {std::vector<double>{0.0, 0.5, 1.0}, std::vector<double>{0.0, 1.0}, std::vector<double>{0.0, 0.5, 1.0}};
  d.periodic = {true, false, true};
  d.ghost_width = 0.05;
  // 2 x 2 on a periodic base: everyone touches everyone (corners included).
  EXPECT_EQ(d.neighbours(0), (std::vector<int>{1, 2, 3}));
  d.periodic = {false, false, false};  // still all: the four columns meet at the centre
  EXPECT_EQ(d.neighbours(3), (std::vector<int>{0, 1, 2}));
  // Four walled slabs: each sees the next ones only; a ghost width wider than a slab reaches on.
  d.shape = {4, 1, 1};
  d.bounds = {std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}, std::vector<double>{0.0, 1.0},
              std::vector<double>{0.0, 1.0}};
  EXPECT_EQ(d.neighbours(0), (std::vector<int>{1}));
  EXPECT_EQ(d.neighbours(2), (std::vector<int>{1, 3}));
  d.periodic[0] = true;
  EXPECT_EQ(d.neighbours(0), (std::vector<int>{1, 3}));  // through the periodic face
  d.ghost_width = 0.3;
  EXPECT_EQ(d.neighbours(0), (std::vector<int>{1, 2, 3}));
}

TEST(DomainDecomposition, RebalancingMovesTheCutsWithTheMaterial) {
  DomainDecomposition d;
  d.shape = {2, 1, 2};
  d.bounds = {std::vector<double>{0.0, 0.5, 1.0}, std::vector<double>{0.0, 1.0}, std::vector<double>{0.0, 0.5, 1.0}};
  // All the material has gathered in x in [0.6, 0.8), spread evenly in z: the x cut moves to 0.7,
  // the z cut stays at 0.5, and the uncut y axis is left alone.
  std::array<std::vector<double>, 3> counts{std::vector<double>(100, 0.0), std::vector<double>(100, 1.0),
                                            std::vector<double>(100, 1.0)};
  for (int b = 60; b < 80; ++b) counts[0][b] = 10.0;
  d.rebalance(counts);
  EXPECT_NEAR(d.bounds[0][1], 0.7, 1e-12);
  EXPECT_NEAR(d.bounds[2][1], 0.5, 1e-12);
  EXPECT_EQ(d.bounds[1], (std::vector<double>{0.0, 1.0}));
  EXPECT_EQ(d.bounds[0].front(), 0.0);
  EXPECT_EQ(d.bounds[0].back(), 1.0);
  EXPECT_EQ(d.bin_of({0.705, 0, 0}, 0, 100), 70);
}

}  // namespace
}  // namespace grainflow::dem
