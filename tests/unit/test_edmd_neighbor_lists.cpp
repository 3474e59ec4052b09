// The event-driven engine's neighbour lists (edmd/neighbor_lists.hpp) on their own: the shell,
// lists that hold every pair within reach (against a brute-force search over all pairs, through
// periodic faces) and stay symmetric through rebuilds, the time a particle takes to leave its
// shell, and the first contact with a listed neighbour against the closed form.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "grainflow/edmd/cell_grid.hpp"
#include "grainflow/edmd/flight.hpp"
#include "grainflow/edmd/neighbor_lists.hpp"

using namespace grainflow;
using namespace grainflow::edmd;

namespace {

PeriodicBox cube(double side, bool periodic) {
  PeriodicBox b;
  b.hi = {side, side, side};
  b.periodic = {periodic, periodic, periodic};
  return b;
}

// Particles at random places in `b` (no care for overlaps: the lists are geometry only), their
// flights, the list path's grid and the lists built over them, as the engine builds them.
template <int Dim>
struct Listed {
  PeriodicBox box;
  std::vector<double> radius;
  std::vector<Flight> nodes;
  CellGrid<Dim> grid;
  NeighborLists<Dim> lists;
  bool configured = false;

  Listed(const PeriodicBox& b, int n, bool mixed_sizes, unsigned seed) : box(b), radius(n), nodes(n) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double max_diameter = 0.0;
    for (int i = 0; i < n; ++i) {
      radius[i] = mixed_sizes ? 0.3 + 0.4 * u(rng) : 0.5;
      max_diameter = std::max(max_diameter, 2.0 * radius[i]);
      for (int a = 0; a < Dim; ++a) nodes[i].x[a] = box.lo[a] + box.length(a) * u(rng);
    }
    configured = lists.configure(box, radius.size(), max_diameter, mixed_sizes ? 0.0 : 0.5);
    if (!configured) return;
    grid.reset(box, lists.cell_width(), std::max(64.0, 4.0 * n), radius.size());
    for (int i = 0; i < n; ++i) grid.insert(nodes, i, grid.cell_of(box, nodes[i].x));
    lists.build(box, grid, nodes, radius);
  }

  // Pairs whose list centres (positions at the last rebuild: `centre`) lie within r_i + r_j + 2
  // shell of each other, by brute force over all pairs and nearest images.
  std::set<std::pair<int, int>> pairs_within_reach(const std::vector<Vec3>& centre) const {
    std::set<std::pair<int, int>> within;
    for (std::size_t i = 0; i < centre.size(); ++i)
      for (std::size_t j = i + 1; j < centre.size(); ++j) {
        const double reach = radius[i] + radius[j] + 2.0 * lists.shell();
        if (norm2(box.minimum_image(centre[i], centre[j])) < reach * reach)
          within.emplace(static_cast<int>(i), static_cast<int>(j));
      }
    return within;
  }

  // Every listed pair (i < j), checking that j lists i whenever i lists j.
  std::set<std::pair<int, int>> listed_pairs() const {
    std::set<std::pair<int, int>> listed;
    for (std::uint32_t i = 0; i < nodes.size(); ++i)
      for (std::uint32_t j : lists.neighbors(i)) {
        EXPECT_NE(i, j);
        const auto back = lists.neighbors(j);
        EXPECT_NE(std::find(back.begin(), back.end(), i), back.end()) << i << " lists " << j << " but not back";
        listed.emplace(std::min(i, j), std::max(i, j));
      }
    return listed;
  }

  // Listed pairs farther apart than reach (beyond the margin for the slots' single precision).
  int listed_beyond_reach(const std::vector<Vec3>& centre) const {
    int beyond = 0;
    for (const auto& [i, j] : listed_pairs()) {
      const double reach = radius[i] + radius[j] + 2.0 * lists.shell() + 1e-4;
      beyond += norm2(box.minimum_image(centre[i], centre[j])) >= reach * reach;
    }
    return beyond;
  }
};

std::vector<Vec3> positions(const std::vector<Flight>& nodes) {
  std::vector<Vec3> x;
  for (const Flight& f : nodes) x.push_back(f.x);
  return x;
}

bool contains_all(const std::set<std::pair<int, int>>& big, const std::set<std::pair<int, int>>& small) {
  return std::includes(big.begin(), big.end(), small.begin(), small.end());
}

}  // namespace

// 0.2 d plus half the mean free path 1 / (sqrt 2 pi n d^2) in 3D, 1 / (2 sqrt 2 n d) in 2D, kept
// within [0.2, 0.6] d.
TEST(NeighborLists, TheShellGrowsWithTheMeanFreePathWithinBounds) {
  const PeriodicBox b = cube(20.0, true);
  const double n3 = 4000.0 / 8000.0;
  const double free_path = 1.0 / (std::sqrt(2.0) * std::numbers::pi * n3);
  EXPECT_NEAR(NeighborLists<3>::shell_fraction(b, 4000, 1.0), 0.2 + 0.5 * free_path, 1e-12);
  const double n2 = 200.0 / 400.0;
  EXPECT_NEAR(NeighborLists<2>::shell_fraction(b, 200, 1.0), 0.2 + 0.5 / (2.0 * std::sqrt(2.0) * n2), 1e-12);
  EXPECT_EQ(NeighborLists<3>::shell_fraction(b, 10, 1.0), 0.6);               // dilute
  EXPECT_NEAR(NeighborLists<3>::shell_fraction(b, 1000000, 1.0), 0.2, 1e-3);  // dense
}

// A periodic axis shorter than three cells of d + 2 shell cannot hold the 27 distinct cells the
// search relies on.
TEST(NeighborLists, NeedThreeCellsAlongEveryPeriodicAxis) {
  NeighborLists<3> lists;
  EXPECT_FALSE(lists.configure(cube(3.0, true), 20, 1.0, 0.5));
  EXPECT_TRUE(lists.configure(cube(3.0, false), 20, 1.0, 0.5));  // walled: no images to tell apart
  EXPECT_TRUE(lists.configure(cube(12.0, true), 500, 1.0, 0.5));
  EXPECT_GE(12.0, 3.0 * lists.cell_width());
  EXPECT_DOUBLE_EQ(lists.cell_width(), 1.0 + 2.0 * lists.shell() * (1.0 + 1e-9));
}

// Every pair within reach is listed, through periodic faces too, lists are symmetric, and no pair
// is listed far beyond reach: equal spheres (the vectorised search) and mixed sizes, 3D and 2D.
TEST(NeighborLists, ListEveryPairWithinReachAndOnlyThose) {
  for (bool mixed : {false, true}) {
    Listed<3> l(cube(9.0, true), 600, mixed, 11);
    ASSERT_TRUE(l.configured);
    const auto centre = positions(l.nodes);
    const auto listed = l.listed_pairs();
    const auto within = l.pairs_within_reach(centre);
    EXPECT_GT(within.size(), 1000u);
    EXPECT_TRUE(contains_all(listed, within)) << "mixed sizes " << mixed;
    EXPECT_EQ(l.listed_beyond_reach(centre), 0) << "mixed sizes " << mixed;
  }
  Listed<2> flat(cube(30.0, true), 500, false, 12);
  ASSERT_TRUE(flat.configured);
  const auto centre = positions(flat.nodes);
  EXPECT_TRUE(contains_all(flat.listed_pairs(), flat.pairs_within_reach(centre)));
  EXPECT_EQ(flat.listed_beyond_reach(centre), 0);
  // Walled: the same, with no images.
  Listed<3> walled(cube(9.0, false), 600, true, 13);
  ASSERT_TRUE(walled.configured);
  const auto walled_centre = positions(walled.nodes);
  EXPECT_TRUE(contains_all(walled.listed_pairs(), walled.pairs_within_reach(walled_centre)));
}

// Rebuilding lists one particle at a time around new positions (wrapped into the box, as the
// engine does) keeps them symmetric and complete; the lists grow when a crowd needs more room.
TEST(NeighborLists, StaySymmetricAndCompleteThroughRebuilds) {
  Listed<3> l(cube(9.0, true), 600, false, 21);
  ASSERT_TRUE(l.configured);
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Vec3> centre = positions(l.nodes);
  for (int step = 0; step < 3000; ++step) {
    const std::uint32_t i = static_cast<std::uint32_t>(rng() % l.nodes.size());
    Flight& f = l.nodes[i];
    for (int a = 0; a < 3; ++a) f.x[a] += l.lists.shell() * u(rng);
    // Now and then a crowd: a particle moved right next to another.
    if (step % 500 == 0) f.x = l.nodes[(i + 1) % l.nodes.size()].x + Vec3{0.1, 0.0, 0.0};
    std::array<std::int32_t, 3> image{};
    l.box.wrap(f.x, image);
    l.lists.rebuild(i, f.x, l.box, l.grid, l.radius);
    centre[i] = f.x;
    EXPECT_EQ(l.grid.cell(static_cast<int>(i)), l.grid.cell_of(l.box, f.x));
  }
  EXPECT_TRUE(contains_all(l.listed_pairs(), l.pairs_within_reach(centre)));
  EXPECT_EQ(l.listed_beyond_reach(centre), 0);
}

// |d + v t| = shell from inside the shell: from the centre at speed u, shell / u; from d along v,
// (shell - |d|) / u; against v, (shell + |d|) / u; at rest never; past the shell at once.
TEST(NeighborLists, TimeToLeaveTheShell) {
  Listed<3> l(cube(9.0, true), 400, false, 31);
  ASSERT_TRUE(l.configured);
  const double shell = l.lists.shell();
  const Vec3 c = l.nodes[7].x;
  const Vec3 v{0.0, 2.0, 0.0};
  EXPECT_NEAR(l.lists.expiry_time(7, c, v), shell / 2.0, 1e-14);
  EXPECT_NEAR(l.lists.expiry_time(7, c + Vec3{0.0, 0.3 * shell, 0.0}, v), 0.7 * shell / 2.0, 1e-14);
  EXPECT_NEAR(l.lists.expiry_time(7, c - Vec3{0.0, 0.3 * shell, 0.0}, v), 1.3 * shell / 2.0, 1e-14);
  // Sideways from an offset start: |(0.6 s, 2 t, 0)| = s, t = 0.8 s / 2.
  EXPECT_NEAR(l.lists.expiry_time(7, c + Vec3{0.6 * shell, 0.0, 0.0}, v), 0.4 * shell, 1e-14);
  EXPECT_EQ(l.lists.expiry_time(7, c, {}), kNever);
  EXPECT_EQ(l.lists.expiry_time(7, c + Vec3{1.01 * shell, 0.0, 0.0}, v), 0.0);
}

TEST(NeighborLists, NearestImageAlongPeriodicAxesOnly) {
  NeighborLists<3> periodic;
  ASSERT_TRUE(periodic.configure(cube(10.0, true), 100, 1.0, 0.5));
  const Vec3 d = periodic.nearest({9.0, -6.0, 4.0});
  EXPECT_DOUBLE_EQ(d.x, -1.0);
  EXPECT_DOUBLE_EQ(d.y, 4.0);
  EXPECT_DOUBLE_EQ(d.z, 4.0);
  NeighborLists<3> walled;
  ASSERT_TRUE(walled.configure(cube(10.0, false), 100, 1.0, 0.5));
  EXPECT_DOUBLE_EQ(walled.nearest({9.0, -6.0, 4.0}).x, 9.0);
}

// Two listed spheres of diameter 1 closing head-on at relative speed u from centre distance D
// touch at (D - 1) / u; the neighbour met first wins; one moving away is never met, and none is
// reported that would come after the best event so far.
TEST(NeighborLists, FirstContactWithAListedNeighbour) {
  PeriodicBox b = cube(12.0, true);
  std::vector<Flight> nodes(3);
  nodes[0].x = {6.0, 6.0, 6.0};
  nodes[1].x = {7.3, 6.0, 6.0};  // 1.3 ahead along x: listed (reach 1 + 2 shell >= 1.4)
  nodes[2].x = {6.0, 4.8, 6.0};  // 1.2 below along y
  nodes[1].v = {-0.5, 0.0, 0.0};
  nodes[2].v = {0.0, 1.0, 0.0};
  for (Flight& f : nodes) f.clock = 2.0;
  const std::vector<double> radius(3, 0.5);
  NeighborLists<3> lists;
  ASSERT_TRUE(lists.configure(b, 3, 1.0, 0.5));
  CellGrid<3> grid;
  grid.reset(b, lists.cell_width(), 64.0, 3);
  for (int i = 0; i < 3; ++i) grid.insert(nodes, i, grid.cell_of(b, nodes[i].x));
  lists.build(b, grid, nodes, radius);
  ASSERT_EQ(lists.neighbors(0).size(), 2u);

  double best = kNever;
  EXPECT_EQ(lists.first_contact(0, nodes, nodes[0].x, nodes[0].v, 2.0, best), 2u);  // 0.2 / 1
  EXPECT_NEAR(best, 0.2, 1e-12);
  nodes[2].v = {0.0, -1.0, 0.0};  // now moving away
  best = kNever;
  EXPECT_EQ(lists.first_contact(0, nodes, nodes[0].x, nodes[0].v, 2.0, best), 1u);  // 0.3 / 0.5
  EXPECT_NEAR(best, 0.6, 1e-12);
  best = 0.1;  // an earlier event: nothing to report
  EXPECT_EQ(lists.first_contact(0, nodes, nodes[0].x, nodes[0].v, 2.0, best), NeighborLists<3>::kNone);
  EXPECT_EQ(best, 0.1);
  // Neighbours are seen where they are now: 1 flew on for 0.1 s from its clock.
  best = kNever;
  EXPECT_EQ(lists.first_contact(0, nodes, nodes[0].x, nodes[0].v, 2.1, best), 1u);
  EXPECT_NEAR(best, 0.25 / 0.5, 1e-12);
  // Through a periodic face: 1 seen across x = 12 from 0 near x = 0.
  nodes[0].x = {0.2, 6.0, 6.0};
  nodes[1].x = {11.0, 6.0, 6.0};  // 1.2 behind, through the face
  nodes[0].v = {-1.0, 0.0, 0.0};
  nodes[1].v = {};
  nodes[2].x = {6.0, 1.0, 6.0};
  for (std::uint32_t i = 0; i < 3; ++i) lists.rebuild(i, nodes[i].x, b, grid, radius);
  ASSERT_EQ(lists.neighbors(0).size(), 1u);
  EXPECT_FALSE(lists.sees_no_images(0));
  best = kNever;
  EXPECT_EQ(lists.first_contact(0, nodes, nodes[0].x, nodes[0].v, 2.0, best), 1u);
  EXPECT_NEAR(best, 0.2, 1e-12);
}
