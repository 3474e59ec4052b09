// Instantaneous collisions of rough inelastic discs and spheres (Campbell 1982 sections 2.11-2.12).
// Normal restitution e (constant, Campbell's impact-speed law, or elastic below a small impact
// speed) and tangential restitution b in [-1, 1] of the contact-point velocity: -1 smooth, 0
// Campbell's fully rough "no relative tangential velocity on departure", +1 elastic rough. The
// moment of inertia is I = q m R^2, q = (k/R)^2 (Campbell's beta: 0.5 discs, 0.4 solid spheres).
// Angular velocities are vectors; in 2D only their z component is non-zero.
#pragma once

#include <cmath>

#include "grainflow/config/restitution_laws.hpp"
#include "grainflow/config/wall_conditions.hpp"
#include "grainflow/core/vec3.hpp"

namespace grainflow::edmd {

// Normal restitution as a function of the normal impact speed.
struct RestitutionLaw {
  using Kind = RestitutionLawKind;  // the registered laws (config/restitution_laws.hpp)
  Kind kind = Kind::constant;
  double value = 1.0;           // e (constant), or e far above elastic_speed
  double velocity_scale = 1.0;  // m/s, campbell: e = (1 + exp(-3 dv / velocity_scale)) / 2
  double elastic_speed = 0.0;   // m/s, impacts slower than this are elastic (all kinds)

  double operator()(double impact_speed) const {
    if (impact_speed < elastic_speed) return 1.0;
    if (kind == Kind::campbell) return 0.5 * (1.0 + std::exp(-3.0 * impact_speed / velocity_scale));
    return value;
  }
};

struct PairBody {
  Vec3& velocity;
  Vec3& angular_velocity;
  double radius, inv_mass, inv_inertia;  // 1/kg, 1/(kg m^2)
};

// Resolves a collision of i and j touching along `normal` (unit, from j to i). Returns the impulse
// on i (kg m/s); j receives its opposite.
inline Vec3 collide_pair(PairBody i, PairBody j, const Vec3& normal, const RestitutionLaw& law,
                         double tangential_restitution) {
  const Vec3 relative = i.velocity - j.velocity;
  const double vn = dot(relative, normal);  // < 0 approaching
  const Vec3 contact = relative - cross(i.radius * i.angular_velocity + j.radius * j.angular_velocity, normal);
  const Vec3 slip = contact - dot(contact, normal) * normal;
  const double e = law(-vn);
  const double normal_mass = 1.0 / (i.inv_mass + j.inv_mass);
  // Effective mass for a tangential impulse at the contact point (translation + rotation of both).
  const double tangential_inv_mass =
      i.inv_mass + j.inv_mass + i.radius * i.radius * i.inv_inertia + j.radius * j.radius * j.inv_inertia;
  Vec3 impulse = (-(1.0 + e) * normal_mass * vn) * normal;
  if (tangential_restitution > -1.0) {
    const Vec3 tangential = (-(1.0 + tangential_restitution) / tangential_inv_mass) * slip;
    impulse += tangential;
    const Vec3 moment = cross(normal, tangential);  // lever -R n for i; +R n with -J for j
    i.angular_velocity -= (i.radius * i.inv_inertia) * moment;
    j.angular_velocity -= (j.radius * j.inv_inertia) * moment;
  }
  i.velocity += i.inv_mass * impulse;
  j.velocity -= j.inv_mass * impulse;
  return impulse;
}

// Wall conditions of Campbell's Couette cell and chute (listings WALLCL), registered in
// config/wall_conditions.hpp: rough sets the contact point's tangential velocity to the wall's
// (tangential restitution 0), no_slip gives the particle centre the wall's tangential velocity with
// its spin unchanged, smooth leaves the tangential velocity untouched.
using WallCondition = grainflow::WallCondition;

// Resolves a collision of a particle with a wall of infinite mass moving at `wall_velocity`;
// `normal` points from the wall into the box. Returns the impulse on the particle.
inline Vec3 collide_wall(PairBody p, const Vec3& normal, const Vec3& wall_velocity, const RestitutionLaw& law,
                         WallCondition condition) {
  const Vec3 relative = p.velocity - wall_velocity;
  const double vn = dot(relative, normal);
  const double e = law(-vn);
  Vec3 impulse = (-(1.0 + e) * vn / p.inv_mass) * normal;
  const Vec3 tangential = relative - vn * normal;
  if (condition == WallCondition::rough) {
    const Vec3 contact = tangential - cross(p.radius * p.angular_velocity, normal);
    const double tangential_inv_mass = p.inv_mass + p.radius * p.radius * p.inv_inertia;
    impulse -= (1.0 / tangential_inv_mass) * contact;
    p.angular_velocity -= (p.radius * p.inv_inertia) * cross(normal, impulse);
  } else if (condition == WallCondition::no_slip) {
    impulse -= (1.0 / p.inv_mass) * tangential;
  }
  p.velocity += p.inv_mass * impulse;
  return impulse;
}

}  // namespace grainflow::edmd
