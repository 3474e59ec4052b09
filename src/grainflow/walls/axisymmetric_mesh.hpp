// Drawing cylinders and cones: the surface of revolution between two heights along an axis, and the
// heights an unbounded one spans inside the box.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "grainflow/walls/surface_contact.hpp"

namespace grainflow::walls {

// [0, length], or for an unbounded axis the heights of the box's corners along it.
inline std::pair<double, double> axial_extent(const Vec3& point, const Vec3& axis, double length, const Vec3& lo,
                                              const Vec3& hi) {
  if (length < std::numeric_limits<double>::infinity()) return {0.0, length};
  double from = std::numeric_limits<double>::infinity(), to = -from;
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 c{corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z};
    const double h = dot(c - point, axis);
    from = std::min(from, h);
    to = std::max(to, h);
  }
  return {from, to};
}

// The band between heights h0 (radius r0) and h1 (radius r1), closed by discs with `caps`.
inline SurfaceMesh axisymmetric_mesh(const Vec3& point, const Vec3& axis, double h0, double h1, double r0, double r1,
                                     bool caps) {
  constexpr int kSides = 64;
  SurfaceMesh m;
  const Vec3 u = perpendicular(axis), v = cross(axis, u);
  for (int ring = 0; ring < 2; ++ring)
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * M_PI * k / kSides;
      const double r = ring ? r1 : r0;
      m.points.push_back(point + (ring ? h1 : h0) * axis + r * (std::cos(a) * u + std::sin(a) * v));
    }
  for (int k = 0; k < kSides; ++k) m.quad(k, (k + 1) % kSides, kSides + (k + 1) % kSides, kSides + k);
  if (caps) {
    for (int ring = 0; ring < 2; ++ring) {
      const int centre = static_cast<int>(m.points.size());
      m.points.push_back(point + (ring ? h1 : h0) * axis);
      for (int k = 0; k < kSides; ++k)
        m.triangles.push_back({centre, ring * kSides + k, ring * kSides + (k + 1) % kSides});
    }
  }
  return m;
}

}  // namespace grainflow::walls
