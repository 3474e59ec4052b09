// Campbell 1982 Appendix A: the momentum balance of an open-channel (chute) flow of depth h,
//   (Gamma cos(alpha) - gamma Fr^2) dh = (sin(alpha) - tau_w P / (rho_p nu_c g b h)) dx,
// with Fr = u_bar / sqrt(g h) and the profile parameters
//   gamma = int_0^1 (nu / nu_bar) (u / u_bar)^2 d(y/h)                  (momentum flux),
//   Gamma = 2 int_0^1 int_(y/h)^1 (nu / nu_bar) d(y'/h) d(y/h)
//         = 2 int_0^1 (y/h) (nu / nu_bar) d(y/h)                        (pressure force),
// nu_bar = (1/h) int_0^h nu dy and u_bar = (1/h) int_0^h u dy. The coefficient of dh vanishes
// where Gamma cos(alpha) = gamma Fr^2: the critical Froude number Fr_c = (Gamma cos(alpha) / gamma)^(1/2)
// divides supercritical (Fr > Fr_c) from subcritical flow. A uniform profile has gamma = Gamma = 1.
#pragma once

#include <span>

namespace grainflow::analysis {

// One strip of a measured profile, piecewise constant: bounds as heights above the bottom.
struct ProfileStrip {
  double lo = 0.0, hi = 0.0;  // m
  double solids_fraction = 0.0;
  double velocity = 0.0;  // m/s along the flow; NaN where the strip held no material
};

struct ProfileParameters {
  double mean_solids_fraction = 0.0;  // nu_bar over [0, h]
  double depth_mean_velocity = 0.0;   // u_bar over [0, h] (over the part where u is defined)
  double gamma = 0.0;
  double Gamma = 0.0;
};

// The integrals over [0, depth], exact for the piecewise-constant profile (a strip cut by the
// depth counts in part; strips above it not at all).
ProfileParameters open_channel_profile_parameters(std::span<const ProfileStrip> strips, double depth);

// (Gamma cos(alpha) / gamma)^(1/2).
double critical_froude_number(const ProfileParameters& p, double cos_alpha);

}  // namespace grainflow::analysis
