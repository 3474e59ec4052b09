// The vibrating floor (Lan 1994 section 2.6.4, DESIGN.md): velocity A_k 2 pi f_k cos(2 pi f_k (t -
// start) + phi_k), zero before `start`, amplitude ramped linearly over `ramp`; its displacement must
// be the integral of that velocity (else the floor's position and velocity disagree and contacts
// with it gain or lose energy).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "grainflow/dem/wall_motion.hpp"

using namespace grainflow;
using namespace grainflow::dem;

namespace {

DriveConfig drive(Vec3 amplitude, Vec3 frequency, Vec3 phase, double start, double ramp) {
  DriveConfig d;
  d.enabled = true;
  d.amplitude = amplitude;
  d.frequency = frequency;
  d.phase = phase;
  d.start = start;
  d.ramp = ramp;
  return d;
}

// Composite Simpson rule of one velocity component over [a, b] with `intervals` (even) sub-intervals.
// The velocity has kinks at `start` and `start + ramp`: callers integrate piecewise between them,
// where it is smooth and Simpson's error is (b - a) h^4 max|v''''| / 180.
double simpson(const std::function<double(double)>& v, double a, double b, int intervals) {
  if (b <= a) return 0.0;
  const double h = (b - a) / intervals;
  double sum = v(a) + v(b);
  for (int k = 1; k < intervals; ++k) sum += (k % 2 ? 4.0 : 2.0) * v(a + k * h);
  return sum * h / 3.0;
}

// Integral of one component of motion.velocity over [0, t], split at the kinks.
double integrate(const WallMotion& motion, int axis, double t, double start, double ramp) {
  auto v = [&](double u) { return motion.velocity(u)[axis]; };
  const double breaks[] = {0.0, std::min(t, std::max(0.0, start)), std::min(t, start + ramp), t};
  double total = 0.0;
  for (int k = 0; k < 3; ++k) total += simpson(v, breaks[k], breaks[k + 1], 200000);
  return total;
}

}  // namespace

TEST(WallMotion, VelocityIsZeroBeforeStartRampedThenFullSinusoid) {
  const double A = 0.005, f = 12.19, phi = 0.7, start = 0.3, ramp = 0.5;
  const DriveConfig d = drive({0.0, A, 0.0}, {0.0, f, 0.0}, {0.0, phi, 0.0}, start, ramp);
  const WallMotion motion({}, &d);
  EXPECT_TRUE(motion.moves());
  const double w = 2.0 * M_PI * f;
  for (double t : {0.0, 0.1, 0.2999}) {
    EXPECT_EQ(motion.velocity(t), Vec3{}) << "t = " << t;
    EXPECT_EQ(motion.displacement(t), Vec3{}) << "t = " << t;
  }
  for (double t : {0.31, 0.45, 0.6, 0.79}) {
    const double s = (t - start) / ramp;  // linear ramp 0 -> 1
    const Vec3 v = motion.velocity(t);
    EXPECT_NEAR(v.y, s * A * w * std::cos(w * (t - start) + phi), 1e-12) << "t = " << t;
    EXPECT_EQ(v.x, 0.0);
    EXPECT_EQ(v.z, 0.0);
  }
  for (double t : {0.8, 0.81, 1.234, 7.5}) {
    EXPECT_NEAR(motion.velocity(t).y, A * w * std::cos(w * (t - start) + phi), 1e-12) << "t = " << t;
  }
  // Velocity is continuous at the end of the ramp.
  EXPECT_NEAR(motion.velocity(start + ramp - 1e-9).y, motion.velocity(start + ramp + 1e-9).y, 1e-6);
}

TEST(WallMotion, NoRampMeansFullAmplitudeAtStart) {
  const DriveConfig d = drive({0.0, 0.002, 0.0}, {0.0, 40.0, 0.0}, {}, 1.0, 0.0);
  const WallMotion motion({}, &d);
  const double v0 = 0.002 * 2.0 * M_PI * 40.0;
  EXPECT_EQ(motion.velocity(0.999).y, 0.0);
  EXPECT_NEAR(motion.velocity(1.0 + 1e-12).y, v0, 1e-9);
  // Without a ramp the displacement is the plain A (sin(w tau + phi) - sin phi).
  EXPECT_NEAR(motion.displacement(1.0 + 0.3 / 40.0).y, 0.002 * std::sin(2.0 * M_PI * 0.3), 1e-15);
}

// Displacement = integral of velocity, checked by Simpson's rule on pieces where the velocity is
// smooth. Error bound (b - a) h^4 max|d4v/dt4| / 180: the stiffest axis (A = 1 mm, f = 50 Hz) has
// |d4v/dt4| <= A w^5 (1 + 4 / (w ramp)) = 3.1e9 m/s^5, the longest piece is 2.05 s, h = 2.05 / 2e5,
// so the error is below 4e-13 m; 1e-10 m leaves room for round-off in the 2e5-term sums. A wrong
// ramp integral (e.g. the ramp ignored in the displacement) is off by ~A, i.e. millimetres.
TEST(WallMotion, DisplacementIsTheIntegralOfVelocity) {
  const double start = 0.25, ramp = 0.6;
  const DriveConfig d = drive({0.001, 0.005, 0.003}, {50.0, 12.19, 7.0}, {0.0, 2.0 * M_PI / 3.0, 4.0}, start, ramp);
  const Vec3 constant{0.01, 0.0, -0.02};
  const WallMotion motion(constant, &d);
  for (double t : {0.1, 0.25, 0.3, 0.5, 0.85, 0.86, 1.3, 2.9}) {
    for (int axis = 0; axis < 3; ++axis) {
      const double numeric = integrate(motion, axis, t, start, ramp);
      EXPECT_NEAR(motion.displacement(t)[axis], numeric, 1e-10) << "t = " << t << " axis " << axis;
    }
  }
  // The ramp matters: at the end of the ramp the displacement differs from the unramped one by ~A.
  const DriveConfig unramped =
      drive({0.001, 0.005, 0.003}, {50.0, 12.19, 7.0}, {0.0, 2.0 * M_PI / 3.0, 4.0}, start, 0.0);
  EXPECT_GT(std::fabs(WallMotion(constant, &unramped).displacement(0.7).y - motion.displacement(0.7).y), 1e-4);
}

TEST(WallMotion, RotaryDriveMovesOnAllThreeAxes) {
  // Eq. (4-1-1): phases 0, 2pi/3, 4pi/3 make |v| constant, v0 sqrt(3/2), after the ramp.
  const double a = 0.008917, f = 50.0, v0 = a * 2.0 * M_PI * f;
  const DriveConfig d = drive({a, a, a}, {f, f, f}, {0.0, 2.0 * M_PI / 3.0, 4.0 * M_PI / 3.0}, 0.5, 1.0);
  const WallMotion motion({}, &d);
  for (double t = 1.5; t < 1.6; t += 0.0037) EXPECT_NEAR(norm(motion.velocity(t)), v0 * std::sqrt(1.5), 1e-12);
  for (int axis = 0; axis < 3; ++axis)
    EXPECT_NEAR(motion.displacement(2.3)[axis], integrate(motion, axis, 2.3, 0.5, 1.0), 1e-10) << "axis " << axis;
}

TEST(WallMotion, StillWallDoesNotMove) {
  const WallMotion still({}, nullptr);
  EXPECT_FALSE(still.moves());
  EXPECT_EQ(still.velocity(3.0), Vec3{});
  EXPECT_EQ(still.displacement(3.0), Vec3{});
  const WallMotion sliding({0.5, 0.0, 0.0}, nullptr);
  EXPECT_TRUE(sliding.moves());
  EXPECT_NEAR(sliding.displacement(2.0).x, 1.0, 1e-15);
  DriveConfig disabled = drive({0.0, 0.01, 0.0}, {0.0, 10.0, 0.0}, {}, 0.0, 0.0);
  disabled.enabled = false;
  EXPECT_EQ(WallMotion({}, &disabled).velocity(0.3), Vec3{});
}
