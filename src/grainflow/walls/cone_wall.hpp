// The cone wall, a frustum (a hopper's or a funnel's wall): `point` on the axis, unit `axis`, radius
// `radius_start` at `point` and `radius_end` at `length` along the axis, particles `inside` (the
// default) or outside. Its open ends' rims are contacts too.
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>

#include "grainflow/config/geometry_keys.hpp"
#include "grainflow/walls/surface_contact.hpp"

namespace grainflow::walls {

struct ConeWall {
  static constexpr std::string_view name = "cone";
  static constexpr std::string_view meaning = "a cone or frustum about any axis (hoppers, funnels), particles inside";
  static void read(TomlReader& table, GeometryKeys& out);
  static ConeWall from_keys(const GeometryKeys& keys);
  static std::optional<KeyProblem> in_plane_problem(const GeometryKeys&, double /*plane_z*/) {
    return KeyProblem{"type", "a cone would push discs off their plane"};
  }

  Vec3 point, axis;                                           // m; unit
  double radius_start = 0.0, radius_end = 0.0, length = 0.0;  // m
  bool inside = true;

  int elements() const { return 1; }
  // In the half-plane (height h along the axis, distance rho from it) the wall is the segment from
  // (0, radius_start) to (length, radius_end): the nearest point of that segment.
  SurfaceContact contact(int /*element*/, const Vec3& x) const {
    const Vec3 d = x - point;
    const double h = dot(d, axis);
    const Vec3 radial = d - h * axis;
    const double rho = norm(radial);
    const Vec3 out = rho > 0.0 ? radial * (1.0 / rho) : perpendicular(axis);
    const double slope = radius_end - radius_start;
    const double span2 = length * length + slope * slope;
    const double t = (h * length + (rho - radius_start) * slope) / span2;
    if (t > 0.0 && t < 1.0) {
      const double span = std::sqrt(span2);
      double nh = slope / span, nr = -length / span;  // towards the axis
      if (!inside) nh = -nh, nr = -nr;
      return {nh * h + nr * (rho - radius_start), nh * axis + nr * out};
    }
    const double end = t <= 0.0 ? 0.0 : length, r = t <= 0.0 ? radius_start : radius_end;
    const double dh = h - end, dr = rho - r;
    const double distance = std::sqrt(dh * dh + dr * dr);
    if (distance == 0.0) return {0.0, t <= 0.0 ? -axis : axis};
    return {distance, (dh / distance) * axis + (dr / distance) * out};
  }
  ConeWall moved(const RigidMotion& m) const {
    ConeWall w = *this;
    w.point = m.point(point);
    w.axis = m.direction(axis);
    return w;
  }
  bool spins_in_place(const Vec3& angular_velocity, const Vec3& origin) const;
  double surface_shift(const Vec3& shift) const { return norm(shift); }
  SurfaceMesh mesh(const Vec3& lo, const Vec3& hi) const;
};

}  // namespace grainflow::walls
