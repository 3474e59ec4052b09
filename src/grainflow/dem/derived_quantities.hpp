// Quantities a user needs before a long DEM run, derived from the case (Lan 1994 sections 2.5, 4.1):
// masses, K2 and e, the time step of eq. (2-5-4), the Hertz-equivalent K1 of eqs. (2-5-5)-(2-5-9),
// the expected overlap at the floor's peak speed, mass hold-up m_t, V_b and Gamma.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/dem/contact_law.hpp"

namespace grainflow::dem {

// eq. (2-5-8): maximum Hertz overlap for an impact at `speed` of a sphere of `mass` and `diameter`.
double hertz_max_overlap(double youngs_modulus, double poisson_ratio, double diameter, double mass, double speed);
// K1 = m (v_max / alpha_max)^2 (after eq. 2-5-9).
double hertz_equivalent_k1(double youngs_modulus, double poisson_ratio, double diameter, double mass, double speed);

inline constexpr int kLanCollisionSteps = 20;  // steps per collision Lan recommends (section 2.5)

// Radius expansion (section 2.2) without particles.expansion_time: the radii grow back over two
// fall times over a diameter, sqrt(2 d / g), or 200 binary contact durations, whichever is longer.
// A radius then grows at most d/2 over 2 sqrt(2 d / g), about 0.18 sqrt(g d), slower than a grain
// falls one diameter, so growth pushes neighbours apart more slowly than gravity brings them
// together, in any consistent units; without gravity the contact durations bound it (overlap
// created per contact, at most 0.25 % of d). For 3 mm beads under 9.81 m/s^2 it is 0.049 s.
inline constexpr double kExpansionFallTimes = 2.0;
inline constexpr double kExpansionContactDurations = 200.0;
double default_expansion_time(double diameter, double gravity, double contact_duration);

// m/s, the peak speed of the driven face (0 without a drive).
double floor_peak_speed(const CaseConfig& c);
// m/s, the impact speed a rate-dependent law (Hertz) is judged at: the largest of the floor's peak
// speed, the fall over one diameter sqrt(2 g d), the initial thermal speed sqrt(D T) (D dimensions) and the initial
// velocity. 0 when nothing moves the particles.
double characteristic_impact_speed(const CaseConfig& c, double diameter, double floor_speed);

struct DerivedQuantities {
  int reference_species = 0;        // the lightest moving species: it sets the time step
  double reference_mass = 0.0;      // kg
  double reference_diameter = 0.0;  // m
  // The contact law's (contact.model): its closed forms for two reference spheres.
  std::string model;
  std::string stiffness_key;             // contact.KEY of the normal stiffness (k1, kn)
  bool calibrated_by_stiffness = false;  // `grainflow calibrate` may choose that key
  double normal_stiffness = 0.0;         // N/m, loading stiffness: overlap estimates v sqrt(m / k)
  double tangential_stiffness = 0.0;     // N/m
  double impact_speed = 0.0;             // m/s, closing speed of the binary contact below (characteristic_impact_speed)
  double restitution = 0.0;              // binary head-on contact
  double contact_duration = 0.0;         // s, binary contact of two reference spheres
  std::vector<CheckLine> law_lines;      // what `grainflow check` prints of the law
  std::optional<ParameterProblem> law_problem;  // parameters the law cannot run
  double time_step = 0.0;      // s, as used: the law's bound with run.collision_steps, or run.time_step
  double time_step_lan = 0.0;  // s, the law's bound with Lan's n = 20 steps per collision
  bool time_step_from_case = false;
  double steps_per_contact = 0.0;              // contact_duration / time_step
  double collision_steps = 0.0;                // n of eq. (2-5-4) for the time step used
  double floor_peak_speed = 0.0;               // m/s, peak speed of the driven face
  double expected_floor_overlap = 0.0;         // m, linear-spring overlap of a reference sphere hit at that speed
  std::optional<double> hertz_k1;              // N/m, when youngs_modulus is given
  double mass_holdup = 0.0;                    // m_t = N pi d^2 / (6 A), eq. (4-1-3)
  double boundary_fluctuation_velocity = 0.0;  // V_b = V / sqrt(g d), V^2 = <v_floor^2>/3 (eq. 4-1-2)
  double shaking_acceleration = 0.0;           // Gamma = a omega^2 / g along gravity
  int gravity_axis = 1;
  double gravity_magnitude = 0.0;  // m/s^2
  double skin = 0.0;               // m
  double cohesion_reach = 0.0;     // m, an adhesive law's largest neck (-detach_overlap at R* = r_max); 0 without
  double expansion_time = 0.0;     // s, radius expansion as used (particles.expansion_time or the default)
  double max_diameter = 0.0;       // m
  long moving_particles = 0, frozen_particles = 0;
};

DerivedQuantities derive(const CaseConfig& c);

}  // namespace grainflow::dem
