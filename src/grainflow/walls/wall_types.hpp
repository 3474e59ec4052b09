// The wall types a [[geometry]] table may name (geometry.type). Adding a type: its own file (a struct
// with name, meaning, read, from_keys, in_plane_problem, elements, contact, moved, spins_in_place, surface_shift and
// mesh, as plane_wall.hpp) and one entry in WallShape; the case loader, writer, the engine's wall loop
// (one instantiation per type: no virtual call per contact) and the snapshots follow.
#pragma once

#include <string>
#include <variant>

#include "grainflow/config/case_config.hpp"
#include "grainflow/walls/cone_wall.hpp"
#include "grainflow/walls/cylinder_wall.hpp"
#include "grainflow/walls/mesh_wall.hpp"
#include "grainflow/walls/plane_wall.hpp"

namespace grainflow::walls {

// The registered types, in the order `type` names list them.
using WallShape = std::variant<PlaneWall, CylinderWall, ConeWall, MeshWall>;

// The case loader's view of every registered type.
GeometrySchemas geometry_schemas();
// "plane, cylinder, cone, mesh", for messages.
std::string wall_type_names();
// The shape a [[geometry]] table describes (its type checked by the loader), at t = 0.
WallShape make_wall_shape(const GeometryConfig& g);
// The key of `g` that would push discs (2D, in the plane z = plane_z) off their plane, and why; or none.
std::optional<KeyProblem> in_plane_problem(const GeometryConfig& g, double plane_z);
// The smallest gap between x and the wall's surface (negative behind a one-sided wall); a mesh,
// two-sided, looks no farther than `reach` and answers `reach` when nothing is nearer.
double nearest_gap(const WallShape& shape, const Vec3& x, double reach);

}  // namespace grainflow::walls
