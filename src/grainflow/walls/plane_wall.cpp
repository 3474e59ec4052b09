#include "grainflow/walls/plane_wall.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/config/toml_reader.hpp"

namespace grainflow::walls {

void PlaneWall::read(TomlReader& r, GeometryKeys& out) {
  out.set_vector("point", r.required_vec3("point"));
  const Vec3 normal = r.required_vec3("normal");
  if (!(norm(normal) > 0.0)) r.fail("normal", "must not be the zero vector");
  out.set_vector("normal", normal * (1.0 / norm(normal)));
  if (r.has("radius") && (r.has("width") || r.has("height")))
    r.fail("radius", "a plane is bounded to a disc (radius) or to a rectangle (width, height), not both");
  if (r.has("hole_radius")) {
    if (r.has("radius") || r.has("width") || r.has("height"))
      r.fail("hole_radius", "a hole is cut in an unbounded plane (not with radius, width or height)");
    const double hole = r.number("hole_radius", 0.0);
    if (!(hole > 0.0)) r.fail("hole_radius", "must be positive");
    out.set_number("hole_radius", hole);
  }
  if (r.has("radius")) {
    const double radius = r.number("radius", 0.0);
    if (!(radius > 0.0)) r.fail("radius", "must be positive");
    out.set_number("radius", radius);
  }
  if (r.has("width") || r.has("height") || r.has("direction")) {
    const double width = r.required_number("width"), height = r.required_number("height");
    if (!(width > 0.0)) r.fail("width", "must be positive");
    if (!(height > 0.0)) r.fail("height", "must be positive");
    const Vec3 n = normal * (1.0 / norm(normal));
    Vec3 direction = r.vec3("direction", perpendicular(n));
    direction -= dot(direction, n) * n;  // into the plane
    if (!(norm(direction) > 1e-9)) r.fail("direction", "must not be along the normal");
    out.set_number("width", width);
    out.set_number("height", height);
    out.set_vector("direction", direction * (1.0 / norm(direction)));
  }
}

PlaneWall PlaneWall::from_keys(const GeometryKeys& k) {
  PlaneWall w;
  w.point = k.vector("point");
  w.normal = k.vector("normal");
  w.direction = perpendicular(w.normal);
  if (k.has("hole_radius")) w.hole = k.number("hole_radius");
  if (k.has("radius")) {
    w.bound = Bound::disc;
    w.radius = k.number("radius");
  } else if (k.has("width")) {
    w.bound = Bound::rectangle;
    w.direction = k.vector("direction");
    w.half_width = 0.5 * k.number("width");
    w.half_height = 0.5 * k.number("height");
  }
  return w;
}

SurfaceContact PlaneWall::rectangle_contact(const Vec3& x) const {
  const Vec3 d = x - point;
  const double h = dot(d, normal);
  const Vec3 across = cross(normal, direction);
  const double u = dot(d, direction), v = dot(d, across);
  const double cu = std::clamp(u, -half_width, half_width), cv = std::clamp(v, -half_height, half_height);
  if (cu == u && cv == v) return {h, normal};
  const Vec3 away = x - (point + cu * direction + cv * across);
  const double distance = norm(away);
  if (distance == 0.0 || h < 0.0) return {distance, normal};  // behind the plane, off the rectangle
  return {distance, away * (1.0 / distance)};
}

bool PlaneWall::spins_in_place(const Vec3& w, const Vec3& origin) const {
  const double rate = norm(w);
  if (rate == 0.0) return true;
  const bool about_normal = norm(cross(w * (1.0 / rate), normal)) < 1e-12;
  if (!about_normal) return false;
  if (bound == Bound::rectangle) return false;
  if (bound == Bound::none && hole == 0.0) return true;
  const Vec3 off = origin - point;  // a disc only about its own axis
  return norm(off - dot(off, normal) * normal) < 1e-12 * (1.0 + radius + hole);  // a disc or hole only about its own axis
}

SurfaceMesh PlaneWall::mesh(const Vec3& lo, const Vec3& hi) const {
  SurfaceMesh m;
  const Vec3 u = direction, v = cross(normal, direction);
  if (bound == Bound::rectangle) {
    for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
      m.points.push_back(point + (a * half_width) * u + (b * half_height) * v);
    m.quad(0, 1, 2, 3);
    return m;
  }
  if (bound == Bound::disc) {
    constexpr int kSides = 48;
    m.points.push_back(point);
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * M_PI * k / kSides;
      m.points.push_back(point + radius * (std::cos(a) * u + std::sin(a) * v));
      m.triangles.push_back({0, 1 + k, 1 + (k + 1) % kSides});
    }
    return m;
  }
  // The polygon where the plane cuts the box: its crossings of the twelve edges, ordered by angle.
  std::vector<Vec3> cut;
  for (int axis = 0; axis < 3; ++axis) {
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    for (int ca = 0; ca < 2; ++ca)
      for (int cb = 0; cb < 2; ++cb) {
        Vec3 p0 = lo, p1 = lo;
        p0[a] = p1[a] = ca ? hi[a] : lo[a];
        p0[b] = p1[b] = cb ? hi[b] : lo[b];
        p1[axis] = hi[axis];
        const double f0 = dot(p0 - point, normal), f1 = dot(p1 - point, normal);
        if ((f0 < 0.0) == (f1 < 0.0) || f0 == f1) continue;
        cut.push_back(p0 + (f0 / (f0 - f1)) * (p1 - p0));
      }
  }
  if (cut.size() < 3) return m;
  if (hole > 0.0) {  // an annulus from the hole's rim out to the cut's farthest corner
    double outer = hole;
    for (const Vec3& p : cut) outer = std::max(outer, norm(p - point));
    constexpr int kSides = 48;
    for (int k = 0; k < kSides; ++k) {
      const double a = 2.0 * M_PI * k / kSides;
      const Vec3 e = std::cos(a) * u + std::sin(a) * v;
      m.points.push_back(point + hole * e);
      m.points.push_back(point + outer * e);
    }
    for (int k = 0; k < kSides; ++k) {
      const int next = (k + 1) % kSides;
      m.quad(2 * k, 2 * k + 1, 2 * next + 1, 2 * next);
    }
    return m;
  }
  Vec3 centre;
  for (const Vec3& p : cut) centre += p;
  centre *= 1.0 / static_cast<double>(cut.size());
  std::sort(cut.begin(), cut.end(), [&](const Vec3& p, const Vec3& q) {
    return std::atan2(dot(p - centre, v), dot(p - centre, u)) < std::atan2(dot(q - centre, v), dot(q - centre, u));
  });
  m.points.push_back(centre);
  for (std::size_t k = 0; k < cut.size(); ++k) {
    m.points.push_back(cut[k]);
    m.triangles.push_back({0, 1 + static_cast<int>(k), 1 + static_cast<int>((k + 1) % cut.size())});
  }
  return m;
}

}  // namespace grainflow::walls
