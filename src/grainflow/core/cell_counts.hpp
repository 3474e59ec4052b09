// Cells per axis of a grid over a box, shared by both engines' grids: each cell at least
// `min_width` wide along the first `dims` axes (one cell along the others), at most `axis_cap` per
// axis, and widened in steps of 1.25 until there are at most `max_cells` in all. A sparse box (a
// few particles in a huge domain) thus gets a grid sized by its particles, not by its volume;
// wider cells only add candidates to a search.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

namespace grainflow {

inline std::array<int, 3> cell_counts(const std::array<double, 3>& lengths, int dims, double min_width, int axis_cap,
                                      double max_cells) {
  std::array<int, 3> cells{1, 1, 1};
  for (double width = min_width;; width *= 1.25) {
    double total = 1.0;
    for (int a = 0; a < dims; ++a) {
      cells[a] = std::min(axis_cap, std::max(1, static_cast<int>(std::floor(lengths[a] / width))));
      total *= cells[a];
    }
    if (total <= max_cells) return cells;
  }
}

}  // namespace grainflow
