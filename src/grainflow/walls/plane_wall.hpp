// The plane wall: `point` on it, `normal` towards the particles' side; unbounded, or bounded to a
// disc (`radius` about `point`) or a rectangle (`width` along `direction`, `height` across it,
// centred on `point`). A bounded plane's edge is a contact too, from the particles' side. The box
// faces are planes of this type.
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
  static std::optional<KeyProblem> in_plane_problem(const GeometryKeys& keys) {
    if (keys.vector("normal").z != 0.0)
      return KeyProblem{"normal", "a plane's normal lies in the plane: its z component must be 0"};
    return std::nullopt;
  }

  enum class Bound { none, disc, rectangle };
  Vec3 point, normal;  // m; unit
  Bound bound = Bound::none;
  double radius = 0.0;       // m, a disc's
  Vec3 direction;            // unit, in the plane: a rectangle's width
  double half_width = 0.0;   // m
  double half_height = 0.0;  // m

  int elements() const { return 1; }
  SurfaceContact contact(int /*element*/, const Vec3& x) const {
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
    return bound == Bound::none ? std::fabs(dot(shift, normal)) : norm(shift);
  }
  SurfaceMesh mesh(const Vec3& lo, const Vec3& hi) const;  // an unbounded plane cut by the box

 private:
  SurfaceContact rectangle_contact(const Vec3& x) const;
};

}  // namespace grainflow::walls
