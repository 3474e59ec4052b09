// Quantities a user needs before a long DEM run, derived from the case (Lan 1994 sections 2.5, 4.1):
// masses, K2 and e, the time step of eq. (2-5-4), the Hertz-equivalent K1 of eqs. (2-5-5)-(2-5-9),
// the expected overlap at the floor's peak speed, mass hold-up m_t, V_b and Gamma.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "grainflow/core/case_config.hpp"

namespace grainflow::dem {

// eq. (2-5-4): dt = (pi e / n) sqrt(m / (2 K1)).
double walton_braun_time_step(double restitution, int collision_steps, double k1, double mass);
// Duration of a Walton–Braun binary contact: loading quarter-period on K1 plus unloading on K2.
double walton_braun_contact_duration(double k1, double k2, double effective_mass);
// eq. (2-5-8): maximum Hertz overlap for an impact at `speed` of a sphere of `mass` and `diameter`.
double hertz_max_overlap(double youngs_modulus, double poisson_ratio, double diameter, double mass, double speed);
// K1 = m (v_max / alpha_max)^2 (after eq. 2-5-9).
double hertz_equivalent_k1(double youngs_modulus, double poisson_ratio, double diameter, double mass, double speed);

struct DerivedQuantities {
  int reference_species = 0;        // the lightest moving species: it sets the time step
  double reference_mass = 0.0;      // kg
  double reference_diameter = 0.0;  // m
  std::string model;
  double k1 = 0.0, k2 = 0.0, restitution = 0.0, tangential_stiffness = 0.0;  // N/m
  double contact_duration = 0.0;         // s, binary contact of two reference spheres
  double time_step = 0.0;                // s, as used
  bool time_step_from_case = false;
  double steps_per_contact = 0.0;        // contact_duration / time_step
  double collision_steps = 0.0;          // n of eq. (2-5-4) for the time step used
  double floor_peak_speed = 0.0;         // m/s, peak speed of the driven face
  double expected_floor_overlap = 0.0;   // m, linear-spring overlap of a reference sphere hit at that speed
  std::optional<double> hertz_k1;        // N/m, when youngs_modulus is given
  double mass_holdup = 0.0;              // m_t = N pi d^2 / (6 A), eq. (4-1-3)
  double boundary_fluctuation_velocity = 0.0;  // V_b = V / sqrt(g d), V^2 = <v_floor^2>/3 (eq. 4-1-2)
  double shaking_acceleration = 0.0;     // Gamma = a omega^2 / g along gravity
  int gravity_axis = 1;
  double gravity_magnitude = 0.0;        // m/s^2
  double skin = 0.0;                     // m
  double max_diameter = 0.0;             // m
  long moving_particles = 0, frozen_particles = 0;
};

DerivedQuantities derive(const CaseConfig& c);

}  // namespace grainflow::dem
