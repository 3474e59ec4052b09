// ParaView output of a surface: VTK PolyData (.vtp) of triangles, as the snapshots draw a wall.
// Plain points and index triples, so that files need not know what a wall is.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow::io {

// ASCII PolyData with `points` and `triangles` (indices into points), written atomically.
void write_vtp(const std::string& path, const std::vector<Vec3>& points,
               const std::vector<std::array<int, 3>>& triangles);

}  // namespace grainflow::io
