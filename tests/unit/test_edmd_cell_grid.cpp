// The event-driven engine's cell grid (edmd/cell_grid.hpp): cells at least the width asked for,
// the cell holding a point, the linked lists threaded through the flight records, the cells
// around a cell with their periodic and Lees–Edwards image shifts, and the time a particle takes
// to leave its cell against closed forms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "grainflow/edmd/cell_grid.hpp"
#include "grainflow/edmd/flight.hpp"

using namespace grainflow;
using namespace grainflow::edmd;

namespace {

PeriodicBox box(const Vec3& hi, bool x, bool y, bool z) {
  PeriodicBox b;
  b.hi = hi;
  b.periodic = {x, y, z};
  return b;
}

// The particles filed in each cell, by walking its list.
template <int Dim>
std::vector<std::set<int>> members(const CellGrid<Dim>& grid, const std::vector<Flight>& nodes) {
  std::vector<std::set<int>> in(grid.size());
  for (std::size_t c = 0; c < grid.size(); ++c)
    for (int j = grid.head(static_cast<int>(c)); j >= 0; j = nodes[j].next) in[c].insert(j);
  return in;
}

}  // namespace

TEST(CellGrid, CellsAreAtLeastTheWidthAskedFor) {
  const PeriodicBox b = box({10.0, 7.0, 5.0}, true, false, true);
  CellGrid<3> grid;
  grid.reset(b, 1.1, 1e6, 0);
  EXPECT_EQ(grid.count(0), 9);  // floor(10 / 1.1)
  EXPECT_EQ(grid.count(1), 6);
  EXPECT_EQ(grid.count(2), 4);
  EXPECT_EQ(grid.size(), 9u * 6u * 4u);
  for (int a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(grid.width(a) * grid.count(a), b.length(a));
  // A cap on the number of cells widens them (core/cell_counts.hpp), never narrows them.
  grid.reset(b, 1.1, 40.0, 0);
  EXPECT_LE(grid.size(), 40u);
  for (int a = 0; a < 3; ++a) EXPECT_GE(grid.width(a), 1.1);
  // In 2D there is one cell along z.
  CellGrid<2> flat;
  flat.reset(b, 1.1, 1e6, 0);
  EXPECT_EQ(flat.count(2), 1);
  EXPECT_EQ(flat.size(), 9u * 6u);
}

TEST(CellGrid, FindsTheCellOfAPointAndItsCoordinates) {
  const PeriodicBox b = box({4.0, 6.0, 8.0}, true, true, true);
  CellGrid<3> grid;
  grid.reset(b, 2.0, 1e6, 0);  // 2 x 3 x 4 cells of side 2
  EXPECT_EQ(grid.cell_of(b, {0.5, 0.5, 0.5}), 0);
  EXPECT_EQ(grid.cell_of(b, {3.0, 5.0, 7.0}), grid.index(1, 2, 3));
  EXPECT_EQ(grid.cell_of(b, {2.0, 2.0, 2.0}), grid.index(1, 1, 1));  // a face belongs to the cell above
  // Just outside by round-off: the edge cells.
  EXPECT_EQ(grid.cell_of(b, {-1e-12, 6.0 + 1e-12, 4.0}), grid.index(0, 2, 2));
  for (int c = 0; c < static_cast<int>(grid.size()); ++c) {
    const auto xyz = grid.coordinates(c);
    EXPECT_EQ(grid.index(xyz[0], xyz[1], xyz[2]), c);
  }
}

TEST(CellGrid, WrapsThroughPeriodicFacesOnly) {
  const PeriodicBox b = box({6.0, 6.0, 6.0}, true, false, true);
  CellGrid<3> grid;
  grid.reset(b, 2.0, 1e6, 0);
  int c = -1, shift = 0;
  EXPECT_TRUE(grid.wrap(b, 0, c, shift));
  EXPECT_EQ(c, 2);
  EXPECT_EQ(shift, -1);  // seen through the image one box length below
  c = 3;
  shift = 0;
  EXPECT_TRUE(grid.wrap(b, 2, c, shift));
  EXPECT_EQ(c, 0);
  EXPECT_EQ(shift, 1);
  c = 1;
  shift = 0;
  EXPECT_TRUE(grid.wrap(b, 1, c, shift));  // inside: unchanged
  EXPECT_EQ(c, 1);
  EXPECT_EQ(shift, 0);
  c = -1;
  EXPECT_FALSE(grid.wrap(b, 1, c, shift));  // y is walled
}

// Filing, moving and re-filing particles keeps every cell's list exactly the particles in it, with
// the links in the flight records.
TEST(CellGrid, ItsListsHoldExactlyTheParticlesFiledInEachCell) {
  const PeriodicBox b = box({10.0, 10.0, 10.0}, true, true, true);
  const int n = 300;
  CellGrid<3> grid;
  grid.reset(b, 1.0, 1e6, n);
  std::vector<Flight> nodes(n);
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> any_cell(0, static_cast<int>(grid.size()) - 1);
  std::vector<int> where(n);
  for (int i = 0; i < n; ++i) grid.insert(nodes, i, where[i] = any_cell(rng));
  for (int step = 0; step < 3000; ++step) {
    const int i = static_cast<int>(rng() % n);
    grid.move(nodes, i, where[i] = any_cell(rng));
  }
  std::vector<std::set<int>> expected(grid.size());
  for (int i = 0; i < n; ++i) {
    expected[where[i]].insert(i);
    EXPECT_EQ(grid.cell(i), where[i]);
  }
  EXPECT_EQ(members(grid, nodes), expected);
}

// In a periodic box of three cells or more per axis the cells around any cell are 27 distinct
// ones, each seen through the shift of the image it lies in; beyond a walled face there are none.
TEST(CellGrid, VisitsTheCellsAroundACellWithTheirImageShifts) {
  const PeriodicBox b = box({6.0, 8.0, 10.0}, true, true, false);
  CellGrid<3> grid;
  grid.reset(b, 2.0, 1e6, 0);  // 3 x 4 x 5
  const std::vector<Flight> nodes;
  const LeesEdwardsImages still;
  std::vector<std::tuple<int, double, double, double>> seen;
  grid.for_each_cell_around(b, {0, 3, 2}, nodes, still, 0.0, 0.0,
                            [&](int cell, const Vec3& shift, const Vec3& v, bool x_images) {
                              EXPECT_FALSE(x_images);
                              EXPECT_EQ(v.x, 0.0);
                              seen.emplace_back(cell, shift.x, shift.y, shift.z);
                            });
  ASSERT_EQ(seen.size(), 27u);
  std::set<int> cells;
  for (const auto& [cell, sx, sy, sz] : seen) {
    cells.insert(cell);
    const auto c = grid.coordinates(cell);
    EXPECT_EQ(sx, c[0] == 2 ? -6.0 : 0.0);  // x = -1 wraps to the last column, one width below
    EXPECT_EQ(sy, c[1] == 0 ? 8.0 : 0.0);   // y = 4 wraps to the first row, one height above
    EXPECT_EQ(sz, 0.0);
  }
  EXPECT_EQ(cells.size(), 27u);

  // At a walled face along z (cell z = 0) the layer below does not exist.
  int count = 0;
  grid.for_each_cell_around(b, {1, 1, 0}, nodes, still, 0.0, 0.0,
                            [&](int, const Vec3&, const Vec3&, bool) { ++count; });
  EXPECT_EQ(count, 18);

  // Images across x move with a Couette cell's width rate.
  grid.for_each_cell_around(b, {0, 1, 1}, nodes, still, 0.0, 0.25, [&](int, const Vec3& shift, const Vec3& v, bool) {
    EXPECT_EQ(v.x, shift.x == 0.0 ? 0.0 : (shift.x < 0.0 ? -0.25 : 0.25));
  });

  // 2D: the 9 cells of the plane.
  CellGrid<2> flat;
  flat.reset(b, 2.0, 1e6, 0);
  count = 0;
  flat.for_each_cell_around(b, {1, 1, 0}, nodes, still, 0.0, 0.0,
                            [&](int, const Vec3&, const Vec3&, bool) { ++count; });
  EXPECT_EQ(count, 9);
}

// Across a Lees–Edwards boundary the image row slides by U t (mod L) at U: every cell of that row
// is visited, with the row's offset and velocity, and x_images set.
TEST(CellGrid, VisitsAWholeSlidingRowAcrossALeesEdwardsBoundary) {
  const PeriodicBox b = box({8.0, 6.0, 1.0}, true, true, true);
  CellGrid<2> grid;
  grid.reset(b, 2.0, 1e6, 0);  // 4 x 3
  const LeesEdwardsImages sheared{0.5};
  const double t = 21.0;  // offset 10.5 mod 8 = 2.5
  int row_above = 0, row_below = 0, plain = 0;
  grid.for_each_cell_around(b, {1, 2, 0}, std::vector<Flight>{}, sheared, t, 0.0,
                            [&](int cell, const Vec3& shift, const Vec3& v, bool x_images) {
                              if (shift.y == 0.0) {
                                ++plain;
                                EXPECT_FALSE(x_images);
                                return;
                              }
                              ++row_above;
                              EXPECT_EQ(shift.y, 6.0);
                              EXPECT_DOUBLE_EQ(shift.x, 2.5);
                              EXPECT_EQ(v.x, 0.5);
                              EXPECT_TRUE(x_images);
                              EXPECT_EQ(grid.coordinates(cell)[1], 0);
                            });
  EXPECT_EQ(row_above, 4);  // the whole row, not three of its cells
  EXPECT_EQ(plain, 6);
  grid.for_each_cell_around(b, {1, 0, 0}, std::vector<Flight>{}, sheared, t, 0.0,
                            [&](int, const Vec3& shift, const Vec3& v, bool) {
                              if (shift.y == 0.0) return;
                              ++row_below;
                              EXPECT_DOUBLE_EQ(shift.x, -2.5);
                              EXPECT_EQ(v.x, -0.5);
                            });
  EXPECT_EQ(row_below, 4);
}

// From the centre of a cell of side w at speed u along one axis a particle leaves through the face
// ahead after w / (2u); thrown up against gravity too slowly to reach the face above, it falls back
// through the face below at the root of w/2 + u t - g t^2 / 2 = 0.
TEST(CellGrid, TimeToLeaveACellAgainstClosedForms) {
  const PeriodicBox b = box({8.0, 8.0, 8.0}, true, false, true);
  CellGrid<3> grid;
  grid.reset(b, 2.0, 1e6, 0);  // cells of side 2
  int face = -1;
  const Vec3 centre{3.0, 3.0, 3.0};  // the cell (1, 1, 1)
  EXPECT_DOUBLE_EQ(grid.exit_time(b, {1, 1, 1}, centre, {0.5, 0.0, 0.0}, {}, 0.0, face), 2.0);
  EXPECT_EQ(face, 1);  // x, upper
  EXPECT_DOUBLE_EQ(grid.exit_time(b, {1, 1, 1}, centre, {0.0, 0.0, -0.25}, {}, 0.0, face), 4.0);
  EXPECT_EQ(face, 4);  // z, lower
  // Up at 1 against g = 2 downwards: it comes back down through the lower face when
  // 1 + t - t^2 = 0, t = (1 + sqrt 5) / 2.
  EXPECT_NEAR(grid.exit_time(b, {1, 1, 1}, centre, {0.0, 0.0, 1.0}, {0.0, 0.0, -2.0}, 0.0, face),
              (1.0 + std::sqrt(5.0)) / 2.0, 1e-12);
  EXPECT_EQ(face, 4);
  // At rest: never.
  EXPECT_EQ(grid.exit_time(b, {1, 1, 1}, centre, {}, {}, 0.0, face), kNever);
  // A walled outer face (y = 0 here) is a wall's business, not a cell face.
  EXPECT_EQ(grid.exit_time(b, {1, 0, 1}, {3.0, 1.0, 3.0}, {0.0, -1.0, 0.0}, {}, 0.0, face), kNever);
  // A periodic outer face is a face: x = 0 after 1 / 1.
  EXPECT_DOUBLE_EQ(grid.exit_time(b, {0, 1, 1}, {1.0, 3.0, 3.0}, {-1.0, 0.0, 0.0}, {}, 0.0, face), 1.0);
  EXPECT_EQ(face, 0);
  // Faces along x stretch with a Couette cell's width: the upper face of cell 1 (x = 4) moves at
  // 2/4 of the width rate; a particle at rest at x = 3 is reached when it has moved by 1.
  EXPECT_DOUBLE_EQ(grid.exit_time(b, {1, 1, 1}, centre, {}, {}, -0.4, face), 1.0 / 0.2);
  EXPECT_EQ(face, 1);
}
