// The mesh wall: a triangle mesh read from an STL file (binary or ASCII), `file` relative to the case
// file; `scale` (file units to the case's), then `rotate_degrees` about `rotate_axis` through the
// file's origin (axis-angle), then `translate`; `closed` = true refuses a mesh with an open edge.
// Contacts are the surface's (mesh_surface.hpp): exact, two-sided, each smooth patch once. The
// triangles stay where the file put them (a tree over them is built once); a moving mesh carries
// its pose, and a centre is taken into the mesh's own frame for each query.
#pragma once

#include <memory>
#include <string_view>

#include "grainflow/config/geometry_keys.hpp"
#include "grainflow/walls/mesh_surface.hpp"
#include "grainflow/walls/surface_contact.hpp"

namespace grainflow::walls {

struct MeshWall {
  static constexpr std::string_view name = "mesh";
  static constexpr std::string_view meaning = "a triangle mesh from an STL file (binary or ASCII)";
  static void read(TomlReader& table, GeometryKeys& out);
  static MeshWall from_keys(const GeometryKeys& keys);
  static std::optional<KeyProblem> in_plane_problem(const GeometryKeys&, double /*plane_z*/) {
    return KeyProblem{"type", "a mesh is a surface in 3D: discs (2D) take plane or cylinder walls"};
  }

  std::shared_ptr<const MeshSurface> surface;  // in the mesh's place at t = 0
  RigidMotion pose;                            // from there to now

  // Each triangle is an element (what the generic loops see: a contact per triangle, without the
  // shared-edge rule; the engine asks `contacts` instead).
  int elements() const { return static_cast<int>(surface->size()); }
  SurfaceContact contact(int element, const Vec3& x) const {
    const SurfaceContact c = surface->touch(static_cast<std::uint32_t>(element), to_mesh(x)).contact;
    return {c.gap, pose.direction(c.normal)};
  }
  MeshWall moved(const RigidMotion& m) const {
    MeshWall w = *this;
    w.pose = m;
    return w;
  }
  // A mesh is not taken for a surface of revolution: any turn moves it.
  bool spins_in_place(const Vec3& angular_velocity, const Vec3&) const { return angular_velocity == Vec3{}; }
  double surface_shift(const Vec3& shift) const { return norm(shift); }
  SurfaceMesh mesh(const Vec3& lo, const Vec3& hi) const;

  // x in the mesh's frame at t = 0.
  Vec3 to_mesh(const Vec3& x) const {
    if (pose.rotation.identity) return x - pose.shift;
    const Rotation back{pose.rotation.axis, pose.rotation.cosine, -pose.rotation.sine, false};
    return pose.origin + back(x - pose.shift - pose.origin);
  }
  // The contacts of a sphere at x, among `candidates` (triangles listed near it), normals in the box.
  int contacts(const Vec3& x, double within, const MeshFacet* candidates, std::size_t count,
               SurfaceContact* out) const {
    const int n = surface->contacts(to_mesh(x), within, candidates, count, out);
    if (!pose.rotation.identity)
      for (int k = 0; k < n; ++k) out[k].normal = pose.direction(out[k].normal);
    return n;
  }
  // The distance from x to the surface, or `reach` when it is farther.
  double nearest_distance(const Vec3& x, double reach) const { return surface->nearest_distance(to_mesh(x), reach); }
};

}  // namespace grainflow::walls
