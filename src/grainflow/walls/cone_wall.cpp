#include "grainflow/walls/cone_wall.hpp"

#include "grainflow/config/toml_reader.hpp"
#include "grainflow/walls/axis_keys.hpp"
#include "grainflow/walls/axisymmetric_mesh.hpp"

namespace grainflow::walls {

void ConeWall::read(TomlReader& r, GeometryKeys& out) {
  read_point_and_axis(r, out);
  const double length = r.required_number("length");
  if (!(length > 0.0)) r.fail("length", "must be positive");
  out.set_number("length", length);
  const double r0 = r.required_number("radius_start"), r1 = r.required_number("radius_end");
  if (r0 < 0.0) r.fail("radius_start", "must not be negative");
  if (r1 < 0.0) r.fail("radius_end", "must not be negative");
  if (r0 == 0.0 && r1 == 0.0) r.fail("radius_end", "a cone needs a radius at one end at least (both are 0)");
  out.set_number("radius_start", r0);
  out.set_number("radius_end", r1);
  out.set_boolean("inside", r.boolean("inside", true));
}

ConeWall ConeWall::from_keys(const GeometryKeys& k) {
  ConeWall w;
  w.point = k.vector("point");
  w.axis = k.vector("axis");
  w.length = k.number("length");
  w.radius_start = k.number("radius_start");
  w.radius_end = k.number("radius_end");
  w.inside = k.boolean("inside");
  return w;
}

bool ConeWall::spins_in_place(const Vec3& w, const Vec3& origin) const {
  return turns_about_axis(w, origin, point, axis, std::max(radius_start, radius_end));
}

SurfaceMesh ConeWall::mesh(const Vec3&, const Vec3&) const {
  return axisymmetric_mesh(point, axis, 0.0, length, radius_start, radius_end, false);
}

}  // namespace grainflow::walls
