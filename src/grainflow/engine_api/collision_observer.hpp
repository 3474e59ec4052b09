// What the event-driven engine reports about each collision, for measurements that need more than
// the running totals of EventCounters: stresses carried by collisions, collision rates and angles,
// where energy is dissipated (observe/collision_stress.hpp). Set with EdmdEngine::set_observer; with
// none set, the engine pays one predictable branch per collision.
//
// Particle indices are those of the engine's particle store (state().particles), which the engine
// reorders once when it is built; the store's `id` gives the case's particle id.
#pragma once

#include <cstdint>

#include "grainflow/core/vec3.hpp"

namespace grainflow::engine_api {

struct PairCollision {
  double time = 0.0;              // s
  std::uint32_t i = 0, j = 0;     // particle indices
  Vec3 xi;                        // m, i's centre at contact
  Vec3 xj;                        // m, the image of j that i met (xi - xj is the minimum-image separation)
  Vec3 contact;                   // m, the contact point, xi - R_i normal
  Vec3 normal;                    // unit, from j to i
  Vec3 impulse;                   // kg m/s, on i (j receives its opposite)
  Vec3 relative_velocity_before;  // m/s, v_i - v_j (j's image) just before the collision
  double dissipated = 0.0;        // J, kinetic energy (translational + rotational) lost
};

struct WallCollision {
  double time = 0.0;          // s
  std::uint32_t i = 0;        // particle index
  int wall = 0;               // index into state().walls
  Vec3 x;                     // m, the particle's centre at contact
  Vec3 contact;               // m, the contact point on the wall plane
  Vec3 impulse;               // kg m/s, on the particle (the wall receives its opposite)
  Vec3 slip_velocity_before;  // m/s, tangential velocity of the particle's contact point relative to the wall
  double dissipated = 0.0;    // J lost, in the wall's frame (>= 0; the moving wall's work J . V is apart)
};

class CollisionObserver {
 public:
  virtual ~CollisionObserver() = default;
  virtual void on_pair(const PairCollision&) {}
  virtual void on_wall(const WallCollision&) {}
};

}  // namespace grainflow::engine_api
