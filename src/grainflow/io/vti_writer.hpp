// ParaView output of fields on a regular grid: VTK XML image data (.vti), one value per cell, the
// cells of an nx x ny x nz grid from `origin` in steps of `spacing` (x fastest). ASCII with 17
// significant digits, so a reader gets the doubles that were written.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow::io {

struct CellArray {
  std::string name;
  int components = 1;          // 1 (scalar), 3 (vector) or 9 (tensor, row-major)
  std::vector<double> values;  // components per cell, cells in order
};

struct ImageGrid {
  std::array<int, 3> cells{};
  Vec3 origin, spacing;  // m
};

// Writes `path` atomically; `field_data` are scalars of the whole data set (ParaView's field data).
void write_vti(const std::string& path, const ImageGrid& grid, const std::vector<CellArray>& cell_data,
               const std::vector<std::pair<std::string, double>>& field_data);

}  // namespace grainflow::io
