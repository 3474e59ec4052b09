// Rolling resistance: a torque that opposes the relative rolling of two touching surfaces, which a
// contact between smooth spheres cannot give (grain shape and asperities in real materials; piles
// then stand at angles of repose that free spheres never reach). The two models of Ai, Chen,
// Rotter & Ooi (Powder Technology 206, 2011) that LIGGGHTS offers as rolling_friction cdt / epsd:
//
// - constant_torque (their model A): M = -mu_r R* F_n w/|w|, w the relative rolling velocity. Simple,
//   but it reverses every step once the rolling stops, so a resting grain rocks.
// - epsd (their model C): an elastic-plastic spring-dashpot in the relative rotation. The spring
//   torque grows by -k_r w dt with k_r = c_k k_n mu_r^2 R*^2 (Iwashita & Oda; c_k = 2.25 in 3D),
//   is capped at mu_r R* F_n (full mobilisation: steady rolling feels the same torque as model A),
//   and a viscous dashpot -eta_r 2 sqrt(I_r k_r) w acts while the spring is below its cap, with
//   I_r = 1 / (1/(I_i + m_i r_i^2) + 1/(I_j + m_j r_j^2)). A resting grain comes to rest.
//
// w = (omega_i - omega_j) less its part along the normal (twisting is not rolling); against a wall,
// omega_j = 0 and R* = r_i. The torque acts on i, its opposite on j: a couple, so no force, and
// linear and angular momentum are kept. It is independent of the contact law, which gives F_n.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "grainflow/config/rolling_models.hpp"
#include "grainflow/core/vec3.hpp"
#include "grainflow/dem/contact_law.hpp"

namespace grainflow {
struct ContactConfig;
}

namespace grainflow::dem {

// The registered models (config/rolling_models.hpp). `none` never reaches the torque: make_engine
// builds an engine without rolling contacts for it (a test of it here would change the force
// loops' floating-point code, and with it long runs' results).
using RollingModel = grainflow::RollingModel;

struct RollingParams {
  RollingModel model = RollingModel::epsd;
  double friction = 0.0;               // mu_r, dimensionless: the torque's cap is mu_r R* F_n
  double damping = 0.0;                // eta_r, epsd: fraction of the dashpot's critical value
  double stiffness_per_radius2 = 0.0;  // N/m, epsd: k_r / R*^2 = c_k k_n mu_r^2
};

// The parameters of contacts with rolling friction `friction` (the pairs' or a wall's) under the
// case's [contact] keys; `normal_stiffness` (N/m) is the law's loading stiffness k_n.
RollingParams rolling_params(const ContactConfig& contact, double friction, double normal_stiffness);

// What `grainflow check` prints: the model, and for epsd the spring of a sphere of `mass` and
// `radius` on a wall (R* = r, I_r = 7/5 m r^2, its stiffest rolling contact) against `time_step`.
std::vector<CheckLine> describe_rolling(const RollingParams& p, double mass, double radius, double time_step);

// The contact's rolling memory: the epsd spring's torque on i, kept in the tangent plane.
struct RollingState {
  Vec3 spring;  // N m
};

// What the rolling model reads of one contact at one instant.
struct RollingKinematics {
  Vec3 normal;                    // unit, from the partner towards i
  Vec3 relative_spin;             // rad/s, omega_i - omega_j (omega_i against a wall)
  double effective_radius = 0.0;  // m, R*
  double rolling_inertia = 0.0;   // kg m^2, I_r (epsd's dashpot only)
  double normal_force = 0.0;      // N, the contact law's normal force (a pull is no load)
};

struct RollingResistance {
  // The torque on i (its opposite acts on j); `dt` advances the spring (0: no time has passed).
  static Vec3 torque(const RollingParams& p, RollingState& s, const RollingKinematics& k, double dt) {
    const Vec3 w = k.relative_spin - dot(k.relative_spin, k.normal) * k.normal;
    const double load = k.normal_force > 0.0 ? k.normal_force : 0.0;
    const double cap = p.friction * k.effective_radius * load;
    if (p.model == RollingModel::constant_torque) {
      const double speed = norm(w);
      return speed > 0.0 ? (-cap / speed) * w : Vec3{};
    }
    // The stored torque turns with the contact: into the current tangent plane, its size kept.
    const double before = norm(s.spring);
    s.spring -= dot(s.spring, k.normal) * k.normal;
    const double after = norm(s.spring);
    if (after > 0.0) s.spring *= before / after;
    const double stiffness = p.stiffness_per_radius2 * k.effective_radius * k.effective_radius;
    s.spring -= (stiffness * dt) * w;
    const double size = norm(s.spring);
    if (size >= cap) {  // full mobilisation: the spring slides at the cap and the dashpot is off
      s.spring = size > 0.0 ? (cap / size) * s.spring : Vec3{};
      return s.spring;
    }
    const double critical = 2.0 * std::sqrt(k.rolling_inertia * stiffness);
    return s.spring - (p.damping * critical) * w;
  }

  // J, what the epsd spring holds: |M|^2 / (2 k_r).
  static double elastic_energy(const RollingParams& p, const RollingState& s, double effective_radius) {
    const double stiffness = p.stiffness_per_radius2 * effective_radius * effective_radius;
    return p.model == RollingModel::epsd && stiffness > 0.0 ? 0.5 * norm2(s.spring) / stiffness : 0.0;
  }

  // kg m^2, I_r from one side's inverse mass and inverse inertia: 1/(I + m r^2), 0 for a body that
  // does not move (a wall, a bump, a frozen grain).
  static double inverse_rolling_inertia(double inv_mass, double inv_inertia, double radius) {
    if (inv_mass == 0.0 || inv_inertia == 0.0) return 0.0;
    return inv_mass * inv_inertia / (inv_mass + radius * radius * inv_inertia);
  }
};

}  // namespace grainflow::dem
