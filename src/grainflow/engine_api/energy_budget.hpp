// A run's energy budget, the same for both engines: what went in (the work of gravity, of moving
// and vibrating walls, the servo and Lees-Edwards boundaries, growing radii), how the particles' energy changed,
// and what collisions and contacts dissipated. input = change + dissipated; the residual says how
// well the bookkeeping closes (event-driven: to round-off; soft spheres: to the integrator's error).
//
// Gravity's work is split by axis. Along axes bounded by walls or open faces it is the change of a
// potential -m g.x, counted in `change`. Along periodic axes (a chute's flow direction) the potential
// has no bound: there its work, m g_a times the unwrapped displacement, is input.
#pragma once

#include <algorithm>
#include <cmath>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/core/vec3.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::engine_api {

struct EnergyBudget {
  double gravity_work = 0.0;     // J, along the periodic axes
  double wall_work = 0.0;        // J, moving and vibrating walls (the servo's included)
  double boundary_work = 0.0;    // J, Lees-Edwards boundaries and periodic images moving with a Couette cell's width
  double growth_work = 0.0;      // J, soft spheres: contacts pushed apart as radii grow (radius expansion)
  double separation_work = 0.0;  // J, event-driven: Campbell's re-separation shifts against gravity
  double change = 0.0;           // J, kinetic + rotational + potential (+ elastic, soft spheres) since the start
  double dissipated = 0.0;       // J, lost in collisions and contacts since the start

  double input() const { return gravity_work + wall_work + boundary_work + growth_work + separation_work; }
  // (input - change - dissipated) / max(|input|, |dissipated|); `fallback_scale` (J) where both
  // are zero (an elastic gas in a box at rest).
  double residual(double fallback_scale) const {
    double scale = std::max(std::fabs(input()), std::fabs(dissipated));
    if (!(scale > 0.0)) scale = std::fabs(fallback_scale);
    return scale > 0.0 ? (input() - change - dissipated) / scale : 0.0;
  }
};

// Kinetic + rotational energy of particle i, translation measured relative to `frame`.
inline double kinetic_energy(const ParticleStore& p, std::size_t i, const Vec3& frame = {}) {
  const double rotational = p.inv_inertia[i] > 0.0 ? 0.5 * norm2(p.angular_velocity[i]) / p.inv_inertia[i] : 0.0;
  return 0.5 * p.mass[i] * norm2(p.velocity[i] - frame) + rotational;
}

// -m g.x of one particle over the axes that are not periodic.
inline double bounded_potential(const PeriodicBox& box, const Vec3& gravity, double mass, const Vec3& x) {
  double u = 0.0;
  for (int a = 0; a < 3; ++a)
    if (!box.periodic[a]) u -= mass * gravity[a] * x[a];
  return u;
}

// Kinetic + rotational + the potential along the bounded axes, summed over the free particles this
// rank integrates (wall bumps move as told; MPI ghosts are another rank's).
inline double mechanical_energy(const ParticleStore& p, const PeriodicBox& box, const Vec3& gravity) {
  double e = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.counted(i)) e += kinetic_energy(p, i) + bounded_potential(box, gravity, p.mass[i], p.position[i]);
  return e;
}

// -sum m g_a x_a over the periodic axes, x unwrapped: its decrease is gravity's work along them.
inline double periodic_potential(const ParticleStore& p, const PeriodicBox& box, const Vec3& gravity) {
  double u = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;
    const Vec3 x = box.unwrapped(p.position[i], p.image[i]);
    for (int a = 0; a < 3; ++a)
      if (box.periodic[a]) u -= p.mass[i] * gravity[a] * x[a];
  }
  return u;
}

}  // namespace grainflow::engine_api
