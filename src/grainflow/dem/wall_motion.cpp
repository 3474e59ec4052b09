#include "grainflow/dem/wall_motion.hpp"

#include <algorithm>
#include <cmath>

namespace grainflow::dem {
namespace {

// Integral over [0, tau] of s(u) A w cos(w u + phi), s(u) = min(1, u / ramp).
double drive_displacement(double amplitude, double omega, double phase, double ramp, double tau) {
  if (tau <= 0.0 || amplitude == 0.0 || omega == 0.0) return 0.0;
  if (ramp <= 0.0) return amplitude * (std::sin(omega * tau + phase) - std::sin(phase));
  const double in_ramp = std::min(tau, ramp);
  // d/du [u sin(wu+phi) + cos(wu+phi)/w] = u w cos(wu+phi)
  double x =
      amplitude / ramp *
      (in_ramp * std::sin(omega * in_ramp + phase) + (std::cos(omega * in_ramp + phase) - std::cos(phase)) / omega);
  if (tau > ramp) x += amplitude * (std::sin(omega * tau + phase) - std::sin(omega * ramp + phase));
  return x;
}

}  // namespace

Vec3 WallMotion::velocity(double t) const {
  Vec3 v = constant_velocity_ + steered_velocity_;
  if (!drive_.enabled) return v;
  const double tau = t - drive_.start;
  if (tau <= 0.0) return v;
  const double ramp = drive_.ramp > 0.0 ? std::min(1.0, tau / drive_.ramp) : 1.0;
  for (int axis = 0; axis < 3; ++axis) {
    const double omega = 2.0 * M_PI * drive_.frequency[axis];
    v[axis] += ramp * drive_.amplitude[axis] * omega * std::cos(omega * tau + drive_.phase[axis]);
  }
  return v;
}

Vec3 WallMotion::displacement(double t) const {
  Vec3 x = constant_velocity_ * t + steered_displacement(t);
  if (!drive_.enabled) return x;
  const double tau = t - drive_.start;
  for (int axis = 0; axis < 3; ++axis) {
    const double omega = 2.0 * M_PI * drive_.frequency[axis];
    x[axis] += drive_displacement(drive_.amplitude[axis], omega, drive_.phase[axis], drive_.ramp, tau);
  }
  return x;
}

}  // namespace grainflow::dem
