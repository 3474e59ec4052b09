// Rolling resistance's parameters from the case (the torque itself is in the header, inlined
// into the engine's force loops).
#include "grainflow/dem/rolling_resistance.hpp"

#include <fmt/format.h>

#include "grainflow/config/case_config.hpp"

namespace grainflow::dem {

RollingParams rolling_params(const ContactConfig& contact, double friction, double normal_stiffness) {
  RollingParams p;
  p.model = rolling_model_named(contact.rolling_model);
  p.friction = friction;
  p.damping = contact.rolling_damping;
  p.stiffness_per_radius2 = contact.rolling_stiffness * normal_stiffness * friction * friction;
  return p;
}

std::vector<CheckLine> describe_rolling(const RollingParams& p, double mass, double radius, double time_step) {
  std::vector<CheckLine> lines;
  if (p.model == RollingModel::none) {
    lines.push_back({"rolling resistance", "none"});
    return lines;
  }
  if (p.model == RollingModel::constant_torque) {
    lines.push_back({"rolling resistance",
                     fmt::format("constant_torque, mu_r = {:.6g}: -mu_r R* F_n along the rolling", p.friction)});
    return lines;
  }
  lines.push_back(
      {"rolling resistance", fmt::format("epsd, mu_r = {:.6g}: spring capped at mu_r R* F_n, dashpot eta_r = {:.3g}",
                                         p.friction, p.damping)});
  const double stiffness = p.stiffness_per_radius2 * radius * radius;
  const double period = 2.0 * M_PI * std::sqrt(1.4 * mass * radius * radius / stiffness);
  lines.push_back({"rolling spring (on a wall)", fmt::format("k_r = {:.6g} N m/rad, period {:.6g} s = {:.4g} steps",
                                                             stiffness, period, period / time_step)});
  return lines;
}

}  // namespace grainflow::dem
