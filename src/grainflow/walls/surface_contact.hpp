// What every wall type answers and shares: where a sphere's centre lies against one element of the
// wall's surface, how the wall's shape follows a rigid motion, and a triangulation to draw it.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow::walls {

// A key of a wall's table that a setting rules out, and why.
struct KeyProblem {
  std::string key, reason;
};

// A centre x against one element of a surface: `gap` is the distance from the nearest surface point
// to x along `normal` (negative behind the surface), `normal` the unit vector from the surface
// towards x. The contact point is x - gap * normal; a sphere of radius r overlaps by r - gap.
struct SurfaceContact {
  double gap = 0.0;
  Vec3 normal;
};

// The rotation by `angle` about the unit `axis` (Rodrigues), or none.
struct Rotation {
  Vec3 axis;
  double cosine = 1.0, sine = 0.0;
  bool identity = true;
  static Rotation about(const Vec3& angular_velocity, double time) {
    const double rate = norm(angular_velocity);
    Rotation r;
    if (rate == 0.0 || time == 0.0) return r;
    r.axis = angular_velocity * (1.0 / rate);
    r.cosine = std::cos(rate * time);
    r.sine = std::sin(rate * time);
    r.identity = false;
    return r;
  }
  Vec3 operator()(const Vec3& v) const {
    if (identity) return v;
    return cosine * v + sine * cross(axis, v) + ((1.0 - cosine) * dot(axis, v)) * axis;
  }
};

// A rigid motion from a wall's initial pose: rotate about `origin` (its place at t = 0), then
// translate by `shift`. With no rotation a point only moves by `shift`, exactly.
struct RigidMotion {
  Vec3 origin, shift;
  Rotation rotation;
  Vec3 point(const Vec3& x) const {
    if (rotation.identity) return x + shift;
    return origin + shift + rotation(x - origin);
  }
  Vec3 direction(const Vec3& d) const { return rotation(d); }
};

// Triangles for drawing a wall (snapshots); indices into `points`.
struct SurfaceMesh {
  std::vector<Vec3> points;
  std::vector<std::array<int, 3>> triangles;
  void quad(int a, int b, int c, int d) {
    triangles.push_back({a, b, c});
    triangles.push_back({a, c, d});
  }
};

// A unit vector perpendicular to the unit vector n (the first axis least aligned with it, projected).
inline Vec3 perpendicular(const Vec3& n) {
  Vec3 e{1.0, 0.0, 0.0};
  if (std::fabs(n.y) < std::fabs(n.x) && std::fabs(n.y) <= std::fabs(n.z)) e = {0.0, 1.0, 0.0};
  else if (std::fabs(n.z) < std::fabs(n.x)) e = {0.0, 0.0, 1.0};
  const Vec3 t = e - dot(e, n) * n;
  return t * (1.0 / norm(t));
}

// The contact of x with a flat disc (centre c, unit normal n towards the particles, radius R): the
// plane's where x's foot lies on the disc, else the rim's nearest point's on the particles' side.
inline SurfaceContact disc_contact(const Vec3& c, const Vec3& n, double radius, const Vec3& x) {
  const Vec3 d = x - c;
  const double h = dot(d, n);
  const Vec3 in_plane = d - h * n;
  const double rho = norm(in_plane);
  if (rho <= radius) return {h, n};
  const Vec3 rim = c + (radius / rho) * in_plane;
  const Vec3 away = x - rim;
  const double distance = norm(away);
  if (distance == 0.0 || h < 0.0) return {distance, n};  // behind the plane, off the disc: no contact there
  return {distance, away * (1.0 / distance)};
}

// The distance from `origin` to the farthest corner of the box [lo, hi]: per radian turned about
// `origin`, no point of a wall inside the box travels farther.
inline double farthest_corner(const Vec3& lo, const Vec3& hi, const Vec3& origin) {
  double d2 = 0.0;
  for (int a = 0; a < 3; ++a) {
    const double far = std::max(std::fabs(lo[a] - origin[a]), std::fabs(hi[a] - origin[a]));
    d2 += far * far;
  }
  return std::sqrt(d2);
}

}  // namespace grainflow::walls
