#include "grainflow/dem/bump_lattice.hpp"

#include <algorithm>
#include <cmath>

namespace grainflow::dem {

double BumpLattice::hole_radius() const {
  if (planar) return 0.5 * line_spacing();
  const double a = column_spacing, b = row_spacing;
  if (!triangular) return 0.5 * std::sqrt(a * a + b * b);
  // Circumradius of the triangle (0,0), (a,0), (a/2,b).
  return (b * b + 0.25 * a * a) / (2.0 * b);
}

double BumpLattice::closest_bumps() const {
  if (planar) return line_spacing();
  const double a = column_spacing, b = row_spacing;
  if (!triangular) return std::min(a, b);
  return std::min(a, std::sqrt(0.25 * a * a + b * b));
}

BumpLattice bump_lattice(const CaseConfig& c, int face) {
  const WallConfig& w = c.walls[face];
  BumpLattice l;
  l.axis = face_axis(face);
  l.axis_a = (l.axis + 1) % 3;
  l.axis_b = (l.axis + 2) % 3;
  l.triangular = w.lattice == "triangular";
  l.bump_diameter = w.bump_diameter > 0.0 ? w.bump_diameter : c.species.front().diameter;
  const double spacing = w.spacing > 0.0 ? w.spacing : l.bump_diameter;
  const double row = l.triangular ? spacing * std::sqrt(3.0) / 2.0 : spacing;
  const double length_a = c.domain.length(l.axis_a), length_b = c.domain.length(l.axis_b);
  l.columns = std::max(1, static_cast<int>(std::lround(length_a / spacing)));
  l.rows = std::max(1, static_cast<int>(std::lround(length_b / row)));
  // A shifted-row lattice only closes across a periodic seam with an even number of rows.
  if (l.triangular && c.domain.periodic(l.axis_b) && l.rows % 2 == 1) l.rows += (l.rows * row < length_b ? 1 : -1);
  l.rows = std::max(l.rows, 1);
  if (c.engine.dimension == 2) {
    l.planar = true;
    l.triangular = false;  // a single row has no shifted rows
    (l.axis_a == 2 ? l.columns : l.rows) = 1;
  }
  l.column_spacing = length_a / l.columns;
  l.row_spacing = length_b / l.rows;
  return l;
}

}  // namespace grainflow::dem
