// Campbell's pressure servo (section 2.14.3, listing COL002) as both engines run it: its units, its
// update triggers with their defaults, the wall-speed rule and the shear-rate rule. The engines
// differ only in how they measure the walls' impulse and move the walls (edmd/couette_servo.hpp,
// dem/dem_couette_servo.hpp).
#pragma once

#include <algorithm>
#include <cmath>

#include "grainflow/config/case_config.hpp"

namespace grainflow {

// The cell as last measured.
struct CouetteServoState {
  double gap = 0.0;              // m, distance between the wall planes
  double width = 0.0;            // m, periodic control-volume width
  double wall_speed = 0.0;       // m/s, opening speed of each wall (> 0 apart)
  double measured_stress = 0.0;  // N/m (2D) or Pa (3D), mean normal stress on the walls over the last period
  double top_speed = 0.0;        // m/s, tangential speed of the top wall
};

struct CouetteServoRule {
  ServoConfig config;        // every_collisions and gap_change resolved (3 N and 0.1 R by default)
  double speed_unit = 1.0;   // m/s, U_T = |v_yhi - v_ylo| at the start
  double stress_unit = 1.0;  // m U_T^2 / R^2 (2D, N/m) or m U_T^2 / R^3 (3D, Pa), m and R of the first species

  static CouetteServoRule from_case(const CaseConfig& c, int dimension) {
    CouetteServoRule rule;
    rule.config = c.servo;
    if (!c.servo.enabled) return rule;
    const SpeciesConfig& first = c.species.front();
    const double radius = 0.5 * first.diameter;
    rule.speed_unit = std::max(norm(c.walls[3].velocity - c.walls[2].velocity), 1e-300);
    rule.stress_unit =
        first.mass(dimension) * rule.speed_unit * rule.speed_unit / (radius * radius * (dimension == 3 ? radius : 1.0));
    long long particles = 0;
    for (const auto& species : c.species) particles += species.count;
    if (rule.config.every_collisions == 0) rule.config.every_collisions = 3 * particles;
    if (rule.config.gap_change == 0.0) rule.config.gap_change = 0.1 * radius;
    return rule;
  }

  // v <- v/2 + (sigma_measured - sigma_target) in Campbell's units (the listing mixes a speed with
  // a stress), clipped to +-sigma_target; `speed` and the result in m/s, > 0 opening the gap.
  double wall_speed(double speed, double measured_stress) const {
    const double target = config.normal_stress / stress_unit;
    const double next = 0.5 * speed / speed_unit + (measured_stress / stress_unit - target);
    return std::clamp(next, -target, target) * speed_unit;
  }

  // The walls' x speeds for U_top - U_bottom = `relative`: the top wall's alone ("top", listing
  // COL002: every reset is a jump of the top wall only), or half the change each in opposite
  // senses about the walls' mean velocity ("both").
  void keep_shear_rate(double& bottom, double& top, double relative) const {
    if (config.shear_rate_walls == "top") {
      top = bottom + relative;
      return;
    }
    const double mean = 0.5 * (bottom + top);
    bottom = mean - 0.5 * relative;
    top = mean + 0.5 * relative;
  }
};

}  // namespace grainflow
