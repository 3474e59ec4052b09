// What a contact law needs to know about one contact at one instant, and what it returns.
// Shared by particle-particle and particle-wall contacts (a wall is a partner of infinite mass).
#pragma once

#include "grainflow/core/vec3.hpp"

namespace grainflow::dem {

struct ContactKinematics {
  Vec3 normal;                    // unit vector from partner j towards particle i
  double overlap = 0.0;           // m, r_i + r_j - |x_i - x_j| (> 0 in contact)
  double normal_velocity = 0.0;   // m/s, (v_i - v_j) . normal (< 0 while approaching)
  Vec3 slip_velocity;             // m/s, tangential velocity of i's contact point relative to j's
  double effective_mass = 0.0;    // kg, m_i m_j / (m_i + m_j); m_i against a wall or frozen partner
  double effective_radius = 0.0;  // m, r_i r_j / (r_i + r_j); r_i against a wall
};

struct ContactForce {
  double normal = 0.0;  // N, force on i along `normal` (> 0 repulsive)
  Vec3 tangential;      // N, tangential force on i (in the tangent plane)
};

}  // namespace grainflow::dem
