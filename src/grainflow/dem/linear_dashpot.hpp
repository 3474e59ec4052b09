// Linear spring–dashpot with tangential history: the physics of LAMMPS `pair_style
// gran/hooke/history`, parameterised the same way (kn, kt, gamma_n, gamma_t, mu), so one case can
// be run in both codes. Damping is per unit effective mass: F_damp = -m_eff * gamma * v.
#pragma once

#include <cmath>

#include "grainflow/dem/contact_kinematics.hpp"

namespace grainflow::dem {

struct LinearDashpot {
  struct Params {
    double kn = 0.0;        // N/m, normal stiffness
    double kt = 0.0;        // N/m, tangential stiffness
    double gamma_n = 0.0;   // 1/s, normal damping rate
    double gamma_t = 0.0;   // 1/s, tangential damping rate
    double friction = 0.0;  // Coulomb coefficient mu
  };

  struct State {
    Vec3 shear;  // m, accumulated tangential displacement, kept in the tangent plane
  };

  static ContactForce force(const Params& p, State& s, const ContactKinematics& c, double dt) {
    ContactForce out;
    // Hookean normal force with velocity damping. As in LAMMPS, the damped force may turn
    // slightly attractive at the end of a contact; restitution and duration have closed forms.
    out.normal = p.kn * c.overlap - c.effective_mass * p.gamma_n * c.normal_velocity;
    if (p.friction <= 0.0 && p.kt <= 0.0) return out;

    // Accumulate the slip, then rotate the stored displacement into the current tangent plane.
    s.shear += c.slip_velocity * dt;
    s.shear -= dot(s.shear, c.normal) * c.normal;
    const Vec3 damping = (c.effective_mass * p.gamma_t) * c.slip_velocity;
    Vec3 ft = -(p.kt * s.shear + damping);
    const double ft_magnitude = norm(ft);
    const double limit = p.friction * std::fabs(out.normal);
    if (ft_magnitude > limit) {
      // Sliding: rescale the stored displacement so spring plus dashpot sit on the Coulomb limit.
      if (norm2(s.shear) != 0.0) {
        const double ratio = limit / ft_magnitude;
        const Vec3 damping_displacement = damping * (1.0 / p.kt);
        s.shear = ratio * (s.shear + damping_displacement) - damping_displacement;
        ft *= ratio;
      } else {
        ft = Vec3{};
      }
    }
    out.tangential = ft;
    return out;
  }

  // Closed forms for a head-on binary contact (no gravity): duration and restitution.
  static double contact_duration(const Params& p, double effective_mass) {
    const double omega0_sq = p.kn / effective_mass;
    const double omega = std::sqrt(omega0_sq - 0.25 * p.gamma_n * p.gamma_n);
    return M_PI / omega;
  }
  static double restitution(const Params& p, double effective_mass) {
    return std::exp(-0.5 * p.gamma_n * contact_duration(p, effective_mass));
  }
};

}  // namespace grainflow::dem
