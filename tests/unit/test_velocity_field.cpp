// The cell-grid velocity field of Lan 1994 Chapter 5 (Fig. 5.1): a particle counts toward the cell
// holding its centre, cell means are plain averages over visits, phase bins collect only their own
// samples, and the convection speed is the visit-weighted mean cell speed (Table 5.1).
#include <gtest/gtest.h>

#include <cmath>

#include "grainflow/observe/velocity_field.hpp"

using namespace grainflow;
using namespace grainflow::observe;

namespace {

void add(ParticleStore& p, Vec3 x, Vec3 v, Motion motion = Motion::free) {
  const std::size_t i = p.size();
  p.resize(i + 1);
  p.position[i] = x;
  p.velocity[i] = v;
  p.radius[i] = p.target_radius[i] = 0.01;
  p.mass[i] = 1.0;
  p.id[i] = static_cast<std::uint32_t>(i);
  p.motion[i] = motion;
}

}  // namespace

// A vortex u = (v_z, v_y) = (-(y - yc), z - zc) sampled at cell centres is recovered exactly; the
// x position (the spanned axis) does not matter; fixed particles and centres outside are ignored.
TEST(VelocityField, CellMeansOfAKnownField) {
  const double cell = 0.1;
  VelocityField field(2, 1, 0.0, 0.6, -0.05, 0.25, cell, 0);
  EXPECT_EQ(field.columns(), 6);
  EXPECT_EQ(field.rows(), 3);
  ParticleStore p;
  for (int col = 0; col < 6; ++col)
    for (int row = 0; row < 3; ++row) {
      const double z = (col + 0.5) * cell, y = -0.05 + (row + 0.5) * cell;
      add(p, {0.37 * col, y, z}, {9.0, z - 0.3, -(y - 0.1)});
    }
  add(p, {0.0, 0.0, 0.05}, {0.0, 100.0, 100.0}, Motion::frozen);
  add(p, {0.0, 0.3, 0.05}, {0.0, 100.0, 100.0});  // above the grid
  field.sample(p, -1);
  for (const FieldCell& c : field.cells()) {
    EXPECT_EQ(c.visits, 1);
    EXPECT_NEAR(c.velocity_horizontal, -(c.vertical - 0.1), 1e-12);
    EXPECT_NEAR(c.velocity_vertical, c.horizontal - 0.3, 1e-12);
  }
}

// Means over visits: two visits at +1 and one at -2 in one cell read 0; the cell's speed and a
// second, steadier cell weight the convection speed by visits: (3 * 0 + 2 * 0.5) / 5 = 0.2.
TEST(VelocityField, VisitWeightedConvectionSpeedAndPhaseBins) {
  VelocityField field(0, 1, 0.0, 2.0, 0.0, 1.0, 1.0, 4);
  ParticleStore a, b;
  add(a, {0.5, 0.5, 0.0}, {0.0, 1.0, 0.0});
  add(a, {1.5, 0.5, 0.0}, {0.3, 0.4, 0.0});
  add(b, {0.5, 0.5, 0.0}, {0.0, 1.0, 0.0});
  add(b, {1.5, 0.5, 0.0}, {0.3, 0.4, 0.0});
  add(b, {0.6, 0.2, 0.0}, {0.0, -2.0, 0.0});
  field.sample(a, 1);
  field.sample(b, 3);
  const auto cells = field.cells();
  EXPECT_EQ(cells[0].visits, 3);
  EXPECT_NEAR(cells[0].velocity_vertical, 0.0, 1e-15);
  EXPECT_NEAR(cells[1].speed(), 0.5, 1e-15);
  EXPECT_NEAR(field.convection_speed(), (3 * 0.0 + 2 * 0.5) / 5.0, 1e-15);
  // Lan's plain mean over cells: (0 + 0.5) / 2. The mean visited cell has 2.5 visits: a cut-off at
  // 0.9 of it (2.25) keeps only the cell of 3, at 1.3 (3.25) none.
  EXPECT_NEAR(field.cell_mean_convection_speed(), 0.25, 1e-15);
  EXPECT_NEAR(field.cell_mean_convection_speed(0.9), 0.0, 1e-15);
  EXPECT_EQ(field.cell_mean_convection_speed(1.3), 0.0);
  // Bin 1 saw only sample a, bin 3 only sample b, bins 0 and 2 nothing.
  EXPECT_EQ(field.cells(1)[0].visits, 1);
  EXPECT_NEAR(field.cells(1)[0].velocity_vertical, 1.0, 1e-15);
  EXPECT_EQ(field.cells(3)[0].visits, 2);
  EXPECT_NEAR(field.cells(3)[0].velocity_vertical, -0.5, 1e-15);
  EXPECT_EQ(field.cells(0)[0].visits, 0);
  EXPECT_EQ(field.samples(), 2);
}
