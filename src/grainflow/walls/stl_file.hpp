// Triangle meshes from STL files (binary or ASCII, told apart by their content): read, welded into
// shared corners, checked and their winding made consistent before a run uses them.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow::walls {

// Triangles sharing their corners. A triangle's corners run counter-clockwise seen from its front,
// the side its normal (b - a) x (c - a) points to.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;  // in the file's order
};

// What reading and checking found.
struct MeshReport {
  bool binary = false;       // the file was binary STL
  std::size_t flipped = 0;   // triangles turned over so that neighbours agree on their front
  bool closed = false;       // every edge is shared by exactly two triangles
  std::size_t pieces = 0;    // connected pieces (triangles joined through shared edges)
};

// Reads `path`, binary or ASCII, and welds corners with identical coordinates. Throws InputError
// naming `path`, `key` (the case key that named the file, for the message) and the reason: a file
// that cannot be read, a truncated binary file, a malformed ASCII line (its line number), no
// triangles, a NaN or infinite coordinate (the triangle's number, counted from 1 in file order).
TriangleMesh read_stl(const std::string& path, const std::string& key, MeshReport* report = nullptr);

// Checks a mesh and repairs its winding, throwing InputError(path, key, reason) that names the
// triangle (counted from 1) for: a degenerate triangle (zero area against the mesh's size), an edge
// shared by more than two triangles, a piece whose winding cannot be made consistent (one-sided, as
// a Moebius strip), and, when `must_be_closed`, an edge of only one triangle. Turns triangles over
// so that every shared edge is walked in opposite directions by its two triangles; a closed piece
// is then turned to face outwards (positive enclosed volume).
MeshReport check_mesh(TriangleMesh& mesh, const std::string& path, const std::string& key, bool must_be_closed);

// Writes `mesh` as STL (binary or ASCII): for tests and tools.
void write_stl(const TriangleMesh& mesh, const std::string& path, bool binary);

}  // namespace grainflow::walls
