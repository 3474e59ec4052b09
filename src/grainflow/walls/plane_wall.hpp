// The plane wall: `point` on it, `normal` towards the particles' side; unbounded, or bounded to a
// disc (`radius` about `point`) or a rectangle (`width` along `direction`, `height` across it,
// centred on `point`). A bounded plane's edge is a contact too, from the particles' side. An
// unbounded plane may have a circular hole (`hole_radius` about `point`; in 2D, with `point` on the
// discs' plane, a slot of that half-width): an orifice. Particles pass through it, so a holed plane
// is two-sided and its hole's rim pushes from either side. The box faces are planes of this type.
#pragma once

#include <string_view>

#include "grainflow/config/geometry_keys.hpp"
#include "grainflow/walls/surface_contact.hpp"

namespace grainflow::walls {

struct PlaneWall {
  static constexpr std::string_view name = "plane";
  static constexpr std::string_view meaning = "a flat wall at any angle, unbounded or a disc or a rectangle";
  static void read(TomlReader& table, GeometryKeys& out);
  static PlaneWall from_keys(const GeometryKeys& keys);
  // Discs (2D) keep every contact normal in the x-y plane: the key that would not, and why; or none.
  // `plane_z`: the discs' plane, where a hole's centre must lie (it is then a slot).
  static std::optional<KeyProblem> in_plane_problem(const GeometryKeys& keys, double plane_z) {
    if (keys.vector("normal").z != 0.0)
      return KeyProblem{"normal", "a plane's normal lies in the plane: its z component must be 0"};
    if (keys.has("hole_radius") && keys.vector("point").z != plane_z)
      return KeyProblem{"point", "a holed plane's point must lie on the discs' plane (z = " + std::to_string(plane_z) +
                                     "): its hole is then a slot of half-width hole_radius"};
    return std::nullopt;
  }

  enum class Bound { none, disc, rectangle };
  Vec3 point, normal;  // m; unit
  Bound bound = Bound::none;
  double radius = 0.0;       // m, a disc's
  Vec3 direction;            // unit, in the plane: a rectangle's width
  double half_width = 0.0;   // m
  double half_height = 0.0;  // m
  double hole = 0.0;         // m, the radius of a hole about `point`, 0 for none

  int elements() const { return 1; }
  SurfaceContact contact(int /*element*/, const Vec3& x) const {
    if (hole > 0.0) return holed_contact(x);
    if (bound == Bound::none) return {dot(x - point, normal), normal};
    if (bound == Bound::disc) return disc_contact(point, normal, radius, x);
    return rectangle_contact(x);
  }
  PlaneWall moved(const RigidMotion& m) const {
    PlaneWall w = *this;
    w.point = m.point(point);
    w.normal = m.direction(normal);
    w.direction = m.direction(direction);
    return w;
  }
  // Whether turning at `angular_velocity` about `origin` leaves the surface where it is.
  bool spins_in_place(const Vec3& angular_velocity, const Vec3& origin) const;
  // How far a translation by `shift` moves the surface at most: an unbounded plane only across itself.
  double surface_shift(const Vec3& shift) const {
    return bound == Bound::none && hole == 0.0 ? std::fabs(dot(shift, normal)) : norm(shift);
  }
  SurfaceMesh mesh(const Vec3& lo, const Vec3& hi) const;  // an unbounded plane cut by the box

 private:
  SurfaceContact rectangle_contact(const Vec3& x) const;
  SurfaceContact holed_contact(const Vec3& x) const {
    const Vec3 d = x - point;
    const double h = dot(d, normal);
    const Vec3 in_plane = d - h * normal;
    const double rho = norm(in_plane);
    if (rho >= hole) return h >= 0.0 ? SurfaceContact{h, normal} : SurfaceContact{-h, -normal};
    const Vec3 out = rho > 0.0 ? in_plane * (1.0 / rho) : perpendicular(normal);
    const Vec3 away = x - (point + hole * out);  // from the hole's rim
    const double distance = norm(away);
    if (distance == 0.0) return {0.0, normal};
    return {distance, away * (1.0 / distance)};
  }
};

}  // namespace grainflow::walls
