// Rolling on a wall (Campbell 1982 section 2.14.2): a particle rebounding from a wall too slowly to
// bounce rolls along it until its next particle collision (bouncing ever closer in time would stop
// the clock). While it rolls it accelerates with the tangential part of gravity, and on rough and
// no-slip walls it rolls without slipping.
#pragma once

#include <cstdint>
#include <vector>

#include "grainflow/core/vec3.hpp"
#include "grainflow/edmd/collision_rules.hpp"
#include "grainflow/edmd/edmd_state.hpp"

namespace grainflow::edmd {

// The acceleration of a particle rolling on `wall`: the tangential part of gravity, reduced by
// 1/(1 + q), q = I / (m R^2), when it rolls without slipping (rough and no-slip walls).
inline Vec3 rolling_acceleration(const Vec3& gravity, const EdmdWall& wall, double mass, double inv_inertia,
                                 double radius) {
  Vec3 a = gravity;
  a[wall.axis] = 0.0;
  if (wall.condition == WallCondition::smooth) return a;
  const double q = 1.0 / (inv_inertia * mass * radius * radius);
  return a * (1.0 / (1.0 + q));
}

// Spin of a particle rolling without slip on `wall` at `velocity`: omega x n R = v_t, the spin about
// the normal n kept. A smooth wall leaves `spin` as it is.
inline Vec3 rolling_spin(const EdmdWall& wall, const Vec3& velocity, const Vec3& spin, double radius) {
  if (wall.condition == WallCondition::smooth) return spin;
  Vec3 n;
  n[wall.axis] = wall.inward;
  const Vec3 slide = velocity - wall.velocity;
  const Vec3 spin_about_normal = dot(spin, n) * n;
  return spin_about_normal + cross(n, slide) * (1.0 / radius);
}

// Which wall each particle rolls on (-1: none) and how many roll now: while none does, nobody
// reads the array (one predictable branch per look).
class RollingWalls {
 public:
  template <class Archive>
  void serialize(Archive& ar) {
    ar(wall_, count_);
  }

  void reset(std::size_t particles) {
    wall_.assign(particles, -1);
    count_ = 0;
  }
  bool any() const { return count_ != 0; }
  bool rolls(std::uint32_t i) const { return count_ != 0 && wall_[i] >= 0; }
  int wall(std::uint32_t i) const { return wall_[i]; }  // -1 when free
  std::size_t size() const { return wall_.size(); }
  void set(std::uint32_t i, int wall) {  // wall -1: i rolls no more
    count_ += (wall >= 0) - (wall_[i] >= 0);
    wall_[i] = wall;
  }

 private:
  std::vector<int> wall_;
  long long count_ = 0;
};

}  // namespace grainflow::edmd
