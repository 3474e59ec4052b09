#include "grainflow/analysis/open_channel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainflow::analysis {

ProfileParameters open_channel_profile_parameters(std::span<const ProfileStrip> strips, double depth) {
  ProfileParameters out;
  double nu = 0.0, nu_y = 0.0, nu_u2 = 0.0, u = 0.0, u_length = 0.0;  // integrals over [0, depth]
  for (const ProfileStrip& s : strips) {
    const double lo = std::max(0.0, s.lo), hi = std::min(depth, s.hi);
    if (!(hi > lo)) continue;
    const double length = hi - lo;
    nu += s.solids_fraction * length;
    nu_y += s.solids_fraction * 0.5 * (hi * hi - lo * lo);
    if (!std::isfinite(s.velocity)) continue;
    nu_u2 += s.solids_fraction * s.velocity * s.velocity * length;
    u += s.velocity * length;
    u_length += length;
  }
  if (!(depth > 0.0) || !(nu > 0.0) || !(u_length > 0.0)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {nan, nan, nan, nan};
  }
  out.mean_solids_fraction = nu / depth;
  out.depth_mean_velocity = u / u_length;
  const double u_bar = out.depth_mean_velocity, nu_bar = out.mean_solids_fraction;
  out.gamma = nu_u2 / (nu_bar * u_bar * u_bar * depth);
  out.Gamma = 2.0 * nu_y / (nu_bar * depth * depth);
  return out;
}

double critical_froude_number(const ProfileParameters& p, double cos_alpha) {
  return std::sqrt(p.Gamma * cos_alpha / p.gamma);
}

}  // namespace grainflow::analysis
