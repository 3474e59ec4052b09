// Walton–Braun contact law (Lan 1994 section 2.4): restitution e = sqrt(K1/K2) for head-on
// impacts, the loading / unloading / reloading paths of Fig. 2.4, and the tangential force.
#include <gtest/gtest.h>

#include <cmath>

#include "grainflow/dem/walton_braun.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

// Integrates a head-on collision of two spheres of masses m1, m2 with velocity Verlet (the
// engine's integrator) and returns the ratio of separation to approach speed.
double head_on_restitution(double k1, double e, double m1, double m2, double speed, int steps_per_contact) {
  const auto params = WaltonBraun::make(k1, e, 0.8, 0.0);
  WaltonBraun::State state;
  const double mu = m1 * m2 / (m1 + m2);
  const double duration = 0.5 * M_PI * (std::sqrt(mu / params.k1) + std::sqrt(mu / params.k2));
  const double dt = duration / steps_per_contact;
  double x1 = 0.0, x2 = 0.0, v1 = speed, v2 = 0.0;  // overlap = x1 - x2 (gap zero at start)
  double f = 0.0;
  for (int step = 0; step < 100 * steps_per_contact; ++step) {
    v1 -= 0.5 * dt * f / m1;
    v2 += 0.5 * dt * f / m2;
    x1 += dt * v1;
    x2 += dt * v2;
    const double overlap = x1 - x2;
    if (overlap <= 0.0 && step > 0) break;
    ContactKinematics c;
    c.normal = {-1.0, 0.0, 0.0};  // from 2 towards 1: sphere 1 approaches from the left
    c.overlap = overlap;
    c.normal_velocity = -(v1 - v2);
    c.effective_mass = mu;
    f = overlap > 0.0 ? WaltonBraun::force(params, state, c, dt).normal : 0.0;
    v1 -= 0.5 * dt * f / m1;
    v2 += 0.5 * dt * f / m2;
  }
  return (v2 - v1) / speed;
}

}  // namespace

// e = sqrt(K1/K2) must hold for any impact speed and mass ratio (eq. 2-4-12); 1% covers the
// time-discretisation error at 50 steps per contact (Verlet error ~ (pi/50)^2 / 2 ~ 0.2%).
TEST(WaltonBraun, HeadOnRestitutionMatchesSqrtK1OverK2) {
  for (double e : {0.5, 0.7, 0.9, 0.95}) {
    for (double speed : {0.01, 0.3, 2.0}) {
      for (double ratio : {1.0, 3.0, 0.1}) {
        const double measured = head_on_restitution(1.0e6, e, 3.5e-5, 3.5e-5 * ratio, speed, 50);
        EXPECT_NEAR(measured, e, 0.01 * e) << "e=" << e << " v=" << speed << " m2/m1=" << ratio;
      }
    }
  }
}
