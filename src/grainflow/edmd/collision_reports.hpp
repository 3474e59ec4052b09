// What the event-driven engine tells a collision observer (engine_api/collision_observer.hpp) about a
// collision it has just resolved. The engine keeps no copy of the state before, so that resolving
// stays as lean as without an observer: what the collision left unchanged (positions, hence
// separation, normal and image frame) is taken as it is, and the velocities before are recovered
// from those after and the impulse J (collide_pair, collide_wall in collision_rules.hpp).
#pragma once

#include <cstdint>

#include "grainflow/core/vec3.hpp"
#include "grainflow/edmd/collision_rules.hpp"
#include "grainflow/edmd/edmd_state.hpp"
#include "grainflow/engine_api/collision_observer.hpp"

namespace grainflow::edmd {

// A particle just after a collision.
struct Collided {
  Vec3 x;                    // m, centre (for a pair's j: of the image i met)
  Vec3 velocity;             // m/s (for a pair's j: of the image i met)
  Vec3 angular_velocity;     // rad/s
  double radius = 0.0;       // m
  double inv_mass = 0.0;     // 1/kg
  double inv_inertia = 0.0;  // 1/(kg m^2)
};

// i and the image of j it met, separated by dr = x_i - x_j, after receiving J and -J:
// v_i' = v_i + J/m_i and v_j' = v_j - J/m_j give the relative velocity before.
inline engine_api::PairCollision pair_collision_report(double time, std::uint32_t i, std::uint32_t j, const Collided& a,
                                                       const Collided& b, const Vec3& dr, const Vec3& impulse,
                                                       double dissipated) {
  const Vec3 normal = dr * (1.0 / norm(dr));
  engine_api::PairCollision c;
  c.time = time;
  c.i = i;
  c.j = j;
  c.xi = a.x;
  c.xj = b.x;
  c.contact = c.xi - a.radius * normal;
  c.normal = normal;
  c.impulse = impulse;
  c.relative_velocity_before = a.velocity - b.velocity - (a.inv_mass + b.inv_mass) * impulse;
  c.dissipated = dissipated;
  return c;
}

// Particle i after its collision with wall w under `condition` (the wall's own, or smooth for a TC
// collision): v' = v + J/m, and on a rough wall omega' = omega - (R/I) n x J; smooth and no-slip
// collisions leave the spin.
inline engine_api::WallCollision wall_collision_report(double time, std::uint32_t i, int w, const EdmdWall& wall,
                                                       const Collided& a, const Vec3& normal, const Vec3& impulse,
                                                       WallCondition condition, double dissipated) {
  Vec3 spin = a.angular_velocity;
  if (condition == WallCondition::rough) spin += (a.radius * a.inv_inertia) * cross(normal, impulse);
  const Vec3 relative = a.velocity - a.inv_mass * impulse - wall.velocity;
  engine_api::WallCollision c;
  c.time = time;
  c.i = i;
  c.wall = w;
  c.x = a.x;
  c.contact = c.x;
  c.contact[wall.axis] = wall.at(time);
  c.impulse = impulse;
  c.slip_velocity_before = relative - dot(relative, normal) * normal - a.radius * cross(spin, normal);
  c.dissipated = dissipated;
  return c;
}

}  // namespace grainflow::edmd
