#include "grainflow/dem/derived_quantities.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/core/ball_measure.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/dem/rolling_resistance.hpp"

namespace grainflow::dem {

double hertz_max_overlap(double youngs_modulus, double poisson_ratio, double diameter, double mass, double speed) {
  const double base = 15.0 * mass * speed * speed * (1.0 - poisson_ratio * poisson_ratio) /
                      (4.0 * youngs_modulus * std::sqrt(diameter));
  return std::pow(base, 0.4);
}

double hertz_equivalent_k1(double youngs_modulus, double poisson_ratio, double diameter, double mass, double speed) {
  const double alpha = hertz_max_overlap(youngs_modulus, poisson_ratio, diameter, mass, speed);
  return mass * (speed / alpha) * (speed / alpha);
}

double default_expansion_time(double diameter, double gravity, double contact_duration) {
  const double fall = gravity > 0.0 ? std::sqrt(2.0 * diameter / gravity) : 0.0;
  return std::max(kExpansionFallTimes * fall, kExpansionContactDurations * contact_duration);
}

double floor_peak_speed(const CaseConfig& c) {
  if (!c.drive.enabled) return 0.0;
  // Maximise |v(t)| over one period numerically (the phases differ by axis).
  double f_min = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    if (c.drive.frequency[axis] > 0.0 && (f_min == 0.0 || c.drive.frequency[axis] < f_min))
      f_min = c.drive.frequency[axis];
  if (f_min == 0.0) return 0.0;
  double speed_sq = 0.0;
  const int samples = 2000;
  for (int k = 0; k < samples; ++k) {
    const double t = k / (samples * f_min);
    double s2 = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double w = 2.0 * M_PI * c.drive.frequency[axis];
      const double v = c.drive.amplitude[axis] * w * std::cos(w * t + c.drive.phase[axis]);
      s2 += v * v;
    }
    speed_sq = std::max(speed_sq, s2);
  }
  return std::sqrt(speed_sq);
}

double characteristic_impact_speed(const CaseConfig& c, double diameter, double floor_speed) {
  const double fall = std::sqrt(2.0 * norm(c.gravity) * diameter);
  const double thermal = std::sqrt(c.engine.dimension * std::max(0.0, c.particles.initial_temperature));
  return std::max({floor_speed, fall, thermal, norm(c.particles.initial_velocity)});
}

DerivedQuantities derive(const CaseConfig& c) {
  DerivedQuantities d;
  d.model = c.contact.model;
  // Reference species: the lightest moving one (shortest contacts).
  double lightest = 0.0;
  for (std::size_t s = 0; s < c.species.size(); ++s) {
    const auto& sp = c.species[s];
    d.max_diameter = std::max(d.max_diameter, sp.diameter);
    if (sp.frozen) continue;
    const double m = sp.mass(c.engine.dimension);
    if (lightest == 0.0 || m < lightest) {
      lightest = m;
      d.reference_species = static_cast<int>(s);
    }
  }
  if (lightest == 0.0) lightest = c.species.front().mass(c.engine.dimension);
  const auto& ref = c.species[d.reference_species];
  d.reference_mass = lightest;
  d.reference_diameter = ref.diameter;

  const double floor_speed = floor_peak_speed(c);
  d.impact_speed = characteristic_impact_speed(c, ref.diameter, floor_speed);
  visit_contact_law(c.contact.model, [&]<ContactLaw Law>() {
    const typename Law::Params p = Law::pair_params(c.contact, ref);
    const HeadOnImpact pair{0.5 * d.reference_mass, 0.25 * ref.diameter, d.impact_speed};
    const BinaryContact binary = Law::binary_contact(p, pair);
    d.stiffness_key = Law::stiffness_key;
    d.calibrated_by_stiffness = Law::calibrated_by_stiffness;
    d.normal_stiffness = Law::loading_stiffness(p, pair);
    d.tangential_stiffness = Law::tangential_stiffness(p, pair);
    d.restitution = binary.restitution;
    d.contact_duration = binary.duration;
    d.law_lines = Law::describe(p, pair);
    d.law_problem = Law::problem(p, pair);
    d.time_step = Law::time_step(p, pair, c.run.collision_steps);
    d.time_step_lan = Law::time_step(p, pair, kLanCollisionSteps);
    if constexpr (CohesiveContactLaw<Law>) {  // R* <= r_max for every pair and wall contact; the neck grows with R*
      const double radius = 0.5 * d.max_diameter;
      d.cohesion_reach = -Law::detach_overlap(p, radius);
      for (int f = 0; f < 6; ++f)
        d.cohesion_reach =
            std::max(d.cohesion_reach, -Law::detach_overlap(Law::wall_params(p, c.walls[f].contact, 0.0), radius));
      for (const GeometryConfig& g : c.geometry)
        d.cohesion_reach = std::max(d.cohesion_reach,
                                    -Law::detach_overlap(Law::wall_params(p, g.material.contact, 0.0), radius));
    }
  });
  if (c.run.time_step > 0.0) {
    d.time_step = c.run.time_step;
    d.time_step_from_case = true;
  }
  if (rolling_model_named(c.contact.rolling_model) != RollingModel::none) {
    const RollingParams rolling = rolling_params(c.contact, c.contact.rolling_friction, d.normal_stiffness);
    for (auto& line : describe_rolling(rolling, d.reference_mass, 0.5 * ref.diameter, d.time_step))
      d.law_lines.push_back(line);
  }
  d.steps_per_contact = d.contact_duration > 0.0 ? d.contact_duration / d.time_step : 0.0;
  // n of eq. (2-5-4) for the step in use: n = pi e sqrt(m / 2K1) / dt.
  d.collision_steps = M_PI * d.restitution * std::sqrt(d.reference_mass / (2.0 * d.normal_stiffness)) / d.time_step;

  // Gravity axis: the axis with the largest gravity component (y when there is none).
  d.gravity_magnitude = norm(c.gravity);
  d.gravity_axis = 1;
  double largest = 0.0;
  for (int axis = 0; axis < 3; ++axis)
    if (std::fabs(c.gravity[axis]) > largest) {
      largest = std::fabs(c.gravity[axis]);
      d.gravity_axis = axis;
    }

  if (c.drive.enabled) {
    double mean_sq = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      const double v0 = c.drive.amplitude[axis] * 2.0 * M_PI * c.drive.frequency[axis];
      mean_sq += 0.5 * v0 * v0;
    }
    d.floor_peak_speed = floor_speed;
    const double mean_diameter_g = ref.diameter * (d.gravity_magnitude > 0.0 ? d.gravity_magnitude : 9.81);
    d.boundary_fluctuation_velocity = std::sqrt(mean_sq / 3.0) / std::sqrt(mean_diameter_g);
    const int g = d.gravity_axis;
    const double omega = 2.0 * M_PI * c.drive.frequency[g];
    if (d.gravity_magnitude > 0.0) d.shaking_acceleration = c.drive.amplitude[g] * omega * omega / d.gravity_magnitude;
  }
  // A sphere hitting the (infinitely heavy) floor at its peak speed: alpha = v sqrt(m / K1).
  d.expected_floor_overlap = d.floor_peak_speed * std::sqrt(d.reference_mass / d.normal_stiffness);
  if (ref.youngs_modulus > 0.0 && d.floor_peak_speed > 0.0)
    d.hertz_k1 =
        hertz_equivalent_k1(ref.youngs_modulus, ref.poisson_ratio, ref.diameter, d.reference_mass, d.floor_peak_speed);

  // Mass hold-up over the floor area normal to gravity (eq. 4-1-3): m_t = sum(pi d^3/6) / (A d); in
  // 2D the floor's length and the discs' areas.
  double area = 1.0;
  for (int axis = 0; axis < c.engine.dimension; ++axis)
    if (axis != d.gravity_axis) area *= c.domain.length(axis);
  double volume = 0.0;
  for (const auto& sp : c.species) {
    if (sp.frozen) {
      d.frozen_particles += sp.count;
      continue;
    }
    d.moving_particles += sp.count;
    volume += sp.count * ball_measure(c.engine.dimension, 0.5 * sp.diameter);
  }
  d.mass_holdup = volume / (area * ref.diameter);
  d.skin = c.run.skin > 0.0 ? c.run.skin : 0.15 * d.max_diameter;
  d.expansion_time = c.particles.expansion_time >= 0.0
                         ? c.particles.expansion_time
                         : default_expansion_time(ref.diameter, d.gravity_magnitude, d.contact_duration);
  return d;
}

}  // namespace grainflow::dem
