// Geometry of a bumpy wall (Lan 1994 section 2.6.3): fixed half-spheres centred on the wall
// plane in a square or triangular lattice. The lattice is stretched slightly so it tiles the face
// exactly (a periodic seam must not open a wider gap); validation and placement both use it.
#pragma once

#include "grainflow/config/case_config.hpp"

namespace grainflow::dem {

struct BumpLattice {
  int axis = 1;                // wall normal axis
  int axis_a = 2, axis_b = 0;  // in-plane axes: columns along a, rows along b
  int columns = 1, rows = 1;
  double column_spacing = 0.0;  // m, along a
  double row_spacing = 0.0;     // m, along b
  bool triangular = false;      // odd rows shifted by half a column
  double bump_diameter = 0.0;   // m
  // 2D: one row of half-discs along the face's in-plane axis (the count along z is 1, on the
  // discs' plane); holes are the gaps between neighbours.
  bool planar = false;
  int line_axis() const { return axis_a == 2 ? axis_b : axis_a; }
  double line_spacing() const { return axis_a == 2 ? row_spacing : column_spacing; }

  // Distance from the centre of the widest hole to its nearest bump centres.
  double hole_radius() const;
  // Smallest centre distance between two bumps (must be >= bump_diameter).
  double closest_bumps() const;
  // Largest free sphere (disc) that could pass between the bumps: 2 (hole_radius - bump radius).
  double largest_passing_diameter() const { return 2.0 * (hole_radius() - 0.5 * bump_diameter); }
};

BumpLattice bump_lattice(const CaseConfig& c, int face);

}  // namespace grainflow::dem
