#include "grainflow/walls/cylinder_wall.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/config/toml_reader.hpp"
#include "grainflow/walls/axis_keys.hpp"
#include "grainflow/walls/axisymmetric_mesh.hpp"

namespace grainflow::walls {

void CylinderWall::read(TomlReader& r, GeometryKeys& out) {
  read_point_and_axis(r, out);
  const double radius = r.required_number("radius");
  if (!(radius > 0.0)) r.fail("radius", "must be positive");
  out.set_number("radius", radius);
  if (r.has("length")) {
    const double length = r.number("length", 0.0);
    if (!(length > 0.0)) r.fail("length", "must be positive (leave it out for an unbounded cylinder)");
    out.set_number("length", length);
  }
  out.set_boolean("inside", r.boolean("inside", true));
  const bool caps = r.boolean("caps", false);
  if (caps && !r.has("length")) r.fail("caps", "an unbounded cylinder has no ends: give its length");
  out.set_boolean("caps", caps);
}

CylinderWall CylinderWall::from_keys(const GeometryKeys& k) {
  CylinderWall w;
  w.point = k.vector("point");
  w.axis = k.vector("axis");
  w.radius = k.number("radius");
  if (k.has("length")) w.length = k.number("length");
  w.inside = k.boolean("inside");
  w.caps = k.boolean("caps");
  return w;
}

bool CylinderWall::spins_in_place(const Vec3& w, const Vec3& origin) const {
  return turns_about_axis(w, origin, point, axis, radius);
}

SurfaceMesh CylinderWall::mesh(const Vec3& lo, const Vec3& hi) const {
  const auto [from, to] = axial_extent(point, axis, length, lo, hi);
  return axisymmetric_mesh(point, axis, from, to, radius, radius, caps);
}

}  // namespace grainflow::walls
