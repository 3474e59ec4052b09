// The cylinder wall: `point` on the axis, unit `axis`, `radius`; `length` from `point` along `axis`
// (unbounded when absent); the particles `inside` (a drum, a container) or outside (a rod). A
// finite cylinder may carry flat `caps` at both ends (elements 1 and 2); an open end's rim is a
// contact too.
#pragma once

#include <limits>
#include <string_view>

#include "grainflow/config/geometry_keys.hpp"
#include "grainflow/walls/surface_contact.hpp"

namespace grainflow::walls {

struct CylinderWall {
  static constexpr std::string_view name = "cylinder";
  static constexpr std::string_view meaning = "a circular cylinder about any axis, particles inside or outside";
  static void read(TomlReader& table, GeometryKeys& out);
  static CylinderWall from_keys(const GeometryKeys& keys);
  static std::optional<KeyProblem> in_plane_problem(const GeometryKeys& keys, double /*plane_z*/) {
    const Vec3 axis = keys.vector("axis");
    if (axis.x != 0.0 || axis.y != 0.0) return KeyProblem{"axis", "a cylinder's axis is along z (a circle)"};
    return std::nullopt;
  }

  Vec3 point, axis;  // m; unit
  double radius = 0.0;
  double length = std::numeric_limits<double>::infinity();
  bool inside = true, caps = false;

  int elements() const { return caps ? 3 : 1; }
  SurfaceContact contact(int element, const Vec3& x) const {
    if (element == 1) return disc_contact(point, inside ? axis : -axis, radius, x);
    if (element == 2) return disc_contact(point + length * axis, inside ? -axis : axis, radius, x);
    const Vec3 d = x - point;
    const double h = dot(d, axis);
    const Vec3 radial = d - h * axis;
    const double rho = norm(radial);
    const Vec3 out = rho > 0.0 ? radial * (1.0 / rho) : perpendicular(axis);
    if (h >= 0.0 && h <= length) return inside ? SurfaceContact{radius - rho, -out} : SurfaceContact{rho - radius, out};
    return rim_contact(x, h < 0.0 ? 0.0 : length, out);
  }
  CylinderWall moved(const RigidMotion& m) const {
    CylinderWall w = *this;
    w.point = m.point(point);
    w.axis = m.direction(axis);
    return w;
  }
  bool spins_in_place(const Vec3& angular_velocity, const Vec3& origin) const;
  double surface_shift(const Vec3& shift) const {
    if (length < std::numeric_limits<double>::infinity()) return norm(shift);
    return norm(shift - dot(shift, axis) * axis);  // an unbounded cylinder only across its axis
  }
  SurfaceMesh mesh(const Vec3& lo, const Vec3& hi) const;

 private:
  SurfaceContact rim_contact(const Vec3& x, double end, const Vec3& out) const {
    const Vec3 away = x - (point + end * axis + radius * out);
    const double distance = norm(away);
    if (distance == 0.0) return {0.0, end == 0.0 ? -axis : axis};
    return {distance, away * (1.0 / distance)};
  }
};

}  // namespace grainflow::walls
