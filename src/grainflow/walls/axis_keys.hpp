// What the walls of revolution (cylinder, cone) share: the keys that place their axis, and the test
// of a turn about that axis, which leaves such a surface where it is.
#pragma once

#include <cmath>

#include "grainflow/config/geometry_keys.hpp"
#include "grainflow/config/toml_reader.hpp"

namespace grainflow::walls {

// `point` on the axis and its direction `axis` (not zero; stored unit).
inline void read_point_and_axis(TomlReader& r, GeometryKeys& out) {
  out.set_vector("point", r.required_vec3("point"));
  const Vec3 axis = r.required_vec3("axis");
  if (!(norm(axis) > 0.0)) r.fail("axis", "must not be the zero vector");
  out.set_vector("axis", axis * (1.0 / norm(axis)));
}

// Whether turning at `angular_velocity` about `origin` turns a surface of revolution (unit `axis`
// through `point`, of size `scale`) about its own axis: along it, through a point of it.
inline bool turns_about_axis(const Vec3& angular_velocity, const Vec3& origin, const Vec3& point, const Vec3& axis,
                             double scale) {
  const double rate = norm(angular_velocity);
  if (rate == 0.0) return true;
  const Vec3 off = origin - point;
  return norm(cross(angular_velocity * (1.0 / rate), axis)) < 1e-12 &&
         norm(off - dot(off, axis) * axis) < 1e-12 * (1.0 + scale);
}

}  // namespace grainflow::walls
