// Walton–Braun contact law (Lan 1994 section 2.4): restitution e = sqrt(K1/K2) for head-on
// impacts, the loading / unloading / reloading paths of Fig. 2.4, the tangential force of
// eqs. (2-4-13)..(2-4-21), and, through the engine, that a contact's memory ends with the contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>
#include <vector>

#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/walton_braun.hpp"
#include "test_support.hpp"

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

// ---------------------------------------------------------------------------------------------
// Normal force paths of Fig. 2.4 (eq. 2-4-1): F = min(K1 alpha, K2 (alpha - alpha0)), never < 0.
// ---------------------------------------------------------------------------------------------
namespace {

// K1 = 1e5 N/m, e = 0.5: K2 = 4 K1, so alpha0 = alpha_max (1 - K1/K2) = 0.75 alpha_max.
constexpr double kK1 = 1.0e5;
constexpr double kE = 0.5;
constexpr double kAlphaB = 2.0e-6;  // m, turning point b of Fig. 2.4

// Normal force at `overlap` for a contact whose memory is `state` (no tangential part).
double normal_force(const WaltonBraun::Params& p, WaltonBraun::State& state, double overlap) {
  ContactKinematics c;
  c.normal = {0.0, 0.0, 1.0};
  c.overlap = overlap;
  c.effective_mass = 1.0e-5;
  return WaltonBraun::force(p, state, c, 1.0e-6).normal;
}

// The law is piecewise linear and evaluated in a handful of flops: the only error allowed is
// round-off, a few ulps of the force scale K1 * alpha_b.
constexpr double kRoundOff = 1.0e-12 * kK1 * kAlphaB;

}  // namespace

// Fig. 2.4a: loading from zero residual overlap follows K1, and the turning point follows alpha.
TEST(WaltonBraun, LoadingFollowsK1) {
  const auto p = WaltonBraun::make(kK1, kE, 0.8, 0.0);
  ASSERT_DOUBLE_EQ(p.k2, 4.0 * kK1);  // eq. (2-4-12): K2 = K1 / e^2
  WaltonBraun::State s;
  for (int k = 1; k <= 20; ++k) {
    const double alpha = kAlphaB * k / 20.0;
    EXPECT_NEAR(normal_force(p, s, alpha), kK1 * alpha, kRoundOff) << "alpha=" << alpha;
    EXPECT_DOUBLE_EQ(s.alpha_max, alpha);
  }
  EXPECT_DOUBLE_EQ(WaltonBraun::residual_overlap(p, s), 0.75 * kAlphaB);
}

// Fig. 2.4b: unloading from b follows K2 down to zero force at alpha0 = alpha_b (1 - K1/K2) and
// the force is zero (never attractive) below alpha0, down to separation.
TEST(WaltonBraun, UnloadingFollowsK2ToResidualOverlapAndNeverAttracts) {
  const auto p = WaltonBraun::make(kK1, kE, 0.8, 0.0);
  WaltonBraun::State s;
  for (int k = 1; k <= 10; ++k) normal_force(p, s, kAlphaB * k / 10.0);
  const double alpha0 = 0.75 * kAlphaB;
  // Chosen overlaps on the unloading line b-c: F = K2 (alpha - alpha0) = 4 K1 (alpha - 0.75 alpha_b).
  for (double fraction : {0.99, 0.95, 0.9, 0.85, 0.8, 0.76}) {
    const double alpha = fraction * kAlphaB;
    const double f = normal_force(p, s, alpha);
    EXPECT_NEAR(f, 4.0 * kK1 * (alpha - alpha0), kRoundOff) << "alpha/alpha_b=" << fraction;
    EXPECT_LT(f, kK1 * alpha);  // below the loading line: energy is lost
    EXPECT_DOUBLE_EQ(s.alpha_max, kAlphaB) << "unloading must not move the turning point";
  }
  EXPECT_NEAR(normal_force(p, s, alpha0), 0.0, kRoundOff);  // point c
  for (double fraction : {0.7, 0.5, 0.25, 1e-3}) {
    EXPECT_EQ(normal_force(p, s, fraction * kAlphaB), 0.0) << "attractive below alpha0 at " << fraction;
  }
  EXPECT_DOUBLE_EQ(s.alpha_max, kAlphaB);
}

// Fig. 2.4c: reloading from c climbs K2 back to b (F2 < F1), then continues on K1 (b-d); a later
// unloading from d uses the new residual overlap alpha_d (1 - K1/K2).
TEST(WaltonBraun, ReloadingClimbsK2BackToBThenContinuesOnK1) {
  const auto p = WaltonBraun::make(kK1, kE, 0.8, 0.0);
  WaltonBraun::State s;
  for (int k = 1; k <= 10; ++k) normal_force(p, s, kAlphaB * k / 10.0);
  normal_force(p, s, 0.5 * kAlphaB);  // unloaded past c: force zero, memory kept
  const double alpha0 = 0.75 * kAlphaB;
  EXPECT_EQ(normal_force(p, s, 0.6 * kAlphaB), 0.0);
  EXPECT_NEAR(normal_force(p, s, alpha0), 0.0, kRoundOff);  // point c
  for (double fraction : {0.8, 0.9, 0.95, 0.99}) {
    const double alpha = fraction * kAlphaB;
    EXPECT_NEAR(normal_force(p, s, alpha), 4.0 * kK1 * (alpha - alpha0), kRoundOff) << "c-b at " << fraction;
  }
  EXPECT_NEAR(normal_force(p, s, kAlphaB), kK1 * kAlphaB, kRoundOff);  // point b: both lines meet
  for (double fraction : {1.05, 1.2, 1.5}) {
    const double alpha = fraction * kAlphaB;
    EXPECT_NEAR(normal_force(p, s, alpha), kK1 * alpha, kRoundOff) << "b-d at " << fraction;
    EXPECT_DOUBLE_EQ(s.alpha_max, alpha);
  }
  // Unloading from d = 1.5 alpha_b: new line through d, zero at 0.75 * 1.5 alpha_b.
  const double alpha_d = 1.5 * kAlphaB;
  for (double fraction : {1.4, 1.3, 1.2}) {
    const double alpha = fraction * kAlphaB;
    EXPECT_NEAR(normal_force(p, s, alpha), 4.0 * kK1 * (alpha - 0.75 * alpha_d), kRoundOff)
        << "d-unload at " << fraction;
  }
  EXPECT_EQ(normal_force(p, s, 1.1 * kAlphaB), 0.0);  // below the new alpha0 = 1.125 alpha_b
}

// Partial unloading (between b and c) and reloading retrace the same K2 line: no energy is lost on
// a closed sub-cycle, and loading resumes on K1 exactly at b.
TEST(WaltonBraun, PartialUnloadReloadRetracesK2Line) {
  const auto p = WaltonBraun::make(kK1, kE, 0.8, 0.0);
  WaltonBraun::State s;
  for (int k = 1; k <= 10; ++k) normal_force(p, s, kAlphaB * k / 10.0);
  const double alpha0 = 0.75 * kAlphaB;
  std::vector<double> down, up;
  for (int k = 0; k <= 10; ++k) down.push_back(normal_force(p, s, kAlphaB * (1.0 - 0.01 * k)));
  for (int k = 10; k >= 0; --k) up.push_back(normal_force(p, s, kAlphaB * (1.0 - 0.01 * k)));
  for (int k = 0; k <= 10; ++k) {
    const double alpha = kAlphaB * (1.0 - 0.01 * k);
    EXPECT_NEAR(down[k], 4.0 * kK1 * (alpha - alpha0), kRoundOff);
    EXPECT_NEAR(up[10 - k], down[k], kRoundOff);
  }
  EXPECT_NEAR(normal_force(p, s, 1.1 * kAlphaB), 1.1 * kK1 * kAlphaB, kRoundOff);
}

// ---------------------------------------------------------------------------------------------
// Tangential force (eqs. 2-4-13 .. 2-4-21).
// ---------------------------------------------------------------------------------------------
namespace {

constexpr double kRatk = 0.8;
constexpr double kMu = 0.5;
constexpr double kOverlap = 1.0e-6;  // m, held fixed on the K1 line: N = K1 alpha = 0.1 N

// One step with surface displacement `slip` (dt = 1 s, so slip_velocity = slip) at fixed overlap.
ContactForce tangential_step(const WaltonBraun::Params& p, WaltonBraun::State& s, const Vec3& slip,
                             const Vec3& normal = {0.0, 0.0, 1.0}) {
  ContactKinematics c;
  c.normal = normal;
  c.overlap = kOverlap;
  c.slip_velocity = slip;
  c.effective_mass = 1.0e-5;
  return WaltonBraun::force(p, s, c, 1.0);
}

// Mindlin-Deresiewicz loading curve that scalek of eq. (2-4-21) integrates to when T* = 0:
// dT/dS = K0 (1 - T/muN)^(1/3)  =>  T(S) = muN [1 - (1 - S/S*)^(3/2)], full sliding at S* = 3 muN / (2 K0).
double mindlin_loading(double s, double mu_n, double k0) {
  const double s_star = 1.5 * mu_n / k0;
  return s >= s_star ? mu_n : mu_n * (1.0 - std::pow(1.0 - s / s_star, 1.5));
}

// The same after a reversal at T* (signed along the old force): the force falls by
// (muN + T*) [1 - (1 - 2 K0 S' / (3 (muN + T*)))^(3/2)] after a reverse slip S'.
double mindlin_unloading(double s_back, double t_star, double mu_n, double k0) {
  const double span = mu_n + t_star;
  const double x = std::max(0.0, 1.0 - 2.0 * k0 * s_back / (3.0 * span));
  return t_star - span * (1.0 - std::pow(x, 1.5));
}

}  // namespace

// First small slip from rest: the force is -K0 dS with K0 = ratk K1 (eq. 2-4-20, scalek = 1),
// opposing the slip, in any tangent direction. Only round-off is allowed.
TEST(WaltonBraun, FirstSlipHasInitialStiffnessK0) {
  const auto p = WaltonBraun::make(kK1, kE, kRatk, kMu);
  ASSERT_DOUBLE_EQ(p.k0, kRatk * kK1);
  for (const Vec3 dir : {Vec3{1.0, 0.0, 0.0}, Vec3{0.0, -1.0, 0.0}, Vec3{0.6, 0.8, 0.0}}) {
    WaltonBraun::State s;
    const Vec3 slip = 1.0e-9 * dir;  // K0 dS = 8e-5 N, far below mu N = 0.05 N
    const ContactForce f = tangential_step(p, s, slip);
    EXPECT_NEAR(f.normal, kK1 * kOverlap, 1e-12 * kK1 * kOverlap);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(f.tangential[a], -p.k0 * slip[a], 1e-12 * p.k0 * 1.0e-9);
  }
}

// Monotonic slip at constant N: the force follows the Mindlin-Deresiewicz curve, with a stiffness
// that only decreases, never exceeds mu N, and then slides at exactly mu N.
TEST(WaltonBraun, MonotonicSlipApproachesCoulombLimitWithDecreasingStiffness) {
  const auto p = WaltonBraun::make(kK1, kE, kRatk, kMu);
  WaltonBraun::State s;
  const double mu_n = kMu * kK1 * kOverlap;
  const double s_star = 1.5 * mu_n / p.k0;
  const int steps = 2000;
  const double ds = s_star / steps;
  double previous = 0.0, previous_increment = p.k0 * ds * (1.0 + 1e-12);
  double max_error = 0.0;
  for (int k = 1; k <= 2 * steps; ++k) {
    const ContactForce f = tangential_step(p, s, {ds, 0.0, 0.0});
    const double t = -f.tangential.x;  // opposes the +x slip
    ASSERT_EQ(f.tangential.y, 0.0);
    ASSERT_EQ(f.tangential.z, 0.0);
    ASSERT_GT(t, 0.0);
    // Coulomb: never above mu N (the clamp rescales by mu N / |F|: a few ulps at most).
    ASSERT_LE(t, mu_n * (1.0 + 1e-14)) << "step " << k;
    const double increment = t - previous;
    ASSERT_GE(increment, -1e-15 * mu_n) << "force fell under monotonic slip at step " << k;
    ASSERT_LE(increment, previous_increment + 1e-15 * mu_n) << "stiffness grew at step " << k;
    previous_increment = increment;
    previous = t;
    max_error = std::max(max_error, std::fabs(t - mindlin_loading(k * ds, mu_n, p.k0)));
  }
  // Each increment uses the stiffness at its start (explicit Euler in S). The slope only falls, so
  // each step under-shoots by at most ds times the slope drop over that step, and the drops sum
  // to at most K0: |T - T_exact| <= K0 ds = 7.5e-4 mu N here (measured: 1.4e-4 mu N).
  EXPECT_LT(max_error, p.k0 * ds);
  // After 2 S* of slip the contact slides: the force sits on mu N to round-off.
  EXPECT_NEAR(previous, mu_n, 1e-12 * mu_n);
  // More slip, any size, keeps it there.
  for (double big : {1e-6, 1e-3}) {
    const ContactForce f = tangential_step(p, s, {big, 0.0, 0.0});
    EXPECT_NEAR(-f.tangential.x, mu_n, 1e-12 * mu_n);
  }
}

// Slip reversal: T* takes the current T, the stiffness is K0 again (the first reverse step changes
// the force by exactly K0 dS) and the force decreases, following the Mindlin unloading curve
// through zero to -mu N; a second reversal again starts with K0.
TEST(WaltonBraun, SlipReversalRestoresK0AndUnloads) {
  const auto p = WaltonBraun::make(kK1, kE, kRatk, kMu);
  const double mu_n = kMu * kK1 * kOverlap;
  const double s_star = 1.5 * mu_n / p.k0;
  const int steps = 2000;
  const double ds = s_star / steps;
  for (double load_fraction : {0.5, 0.9, 2.0}) {  // partial loading, near the limit, full sliding
    WaltonBraun::State s;
    const int forward = static_cast<int>(load_fraction * steps);
    for (int k = 0; k < forward; ++k) tangential_step(p, s, {ds, 0.0, 0.0});
    const double t_star = -s.tangential_force.x;
    ASSERT_GT(t_star, 0.0);
    // The force on i before reversal is -x; reverse slip (-x) unloads it.
    double previous = t_star;
    {
      const ContactForce f = tangential_step(p, s, {-ds, 0.0, 0.0});
      const double t = -f.tangential.x;
      // Exactly K0 ds up to round-off: the difference of two forces ~T* = up to 2000 K0 ds loses
      // ~3 of 16 digits, so 1e-9 relative is still only round-off.
      EXPECT_NEAR(previous - t, p.k0 * ds, 1e-9 * p.k0 * ds) << "stiffness after reversal must be K0";
      EXPECT_DOUBLE_EQ(s.t_star, t_star);
      previous = t;
    }
    double max_error = 0.0;
    bool crossed = false;
    const double back_star = 3.0 * (mu_n + t_star) / (2.0 * p.k0);  // reverse slip to reach -mu N
    for (int k = 2; k * ds <= 1.2 * back_star; ++k) {
      const ContactForce f = tangential_step(p, s, {-ds, 0.0, 0.0});
      const double t = -f.tangential.x;  // signed along the original force direction
      ASSERT_LE(t, previous + 1e-15 * mu_n) << "force grew during unloading at step " << k;
      ASSERT_LE(std::fabs(t), mu_n * (1.0 + 1e-14));
      crossed = crossed || t < 0.0;
      // Same explicit-Euler bound K0 ds as for loading (the span is mu N + T* instead of mu N).
      max_error = std::max(max_error, std::fabs(t - mindlin_unloading(k * ds, t_star, mu_n, p.k0)));
      previous = t;
    }
    EXPECT_TRUE(crossed);
    EXPECT_LT(max_error, p.k0 * ds) << "load fraction " << load_fraction;
    EXPECT_NEAR(previous, -mu_n, 1e-12 * mu_n) << "slides at -mu N after the full reversal";
  }
  // Second reversal from partial unloading: again K0, and the force grows back.
  WaltonBraun::State s;
  for (int k = 0; k < steps / 2; ++k) tangential_step(p, s, {ds, 0.0, 0.0});
  for (int k = 0; k < steps / 4; ++k) tangential_step(p, s, {-ds, 0.0, 0.0});
  const double before = -s.tangential_force.x;
  const ContactForce f = tangential_step(p, s, {ds, 0.0, 0.0});
  EXPECT_NEAR(-f.tangential.x - before, p.k0 * ds, 1e-9 * p.k0 * ds);  // same round-off argument
}

// Eq. (2-4-16): the old force is carried into the current tangent plane (its normal component
// removed) before the increment, so the force stays perpendicular to the rotating normal.
TEST(WaltonBraun, OldForceProjectedIntoNewTangentPlane) {
  const auto p = WaltonBraun::make(kK1, kE, kRatk, kMu);
  WaltonBraun::State s;
  const double mu_n = kMu * kK1 * kOverlap;
  const double s_star = 1.5 * mu_n / p.k0;
  for (int k = 0; k < 100; ++k) tangential_step(p, s, {0.3 * s_star / 100, 0.1 * s_star / 100, 0.0});
  const Vec3 old_force = s.tangential_force;
  ASSERT_GT(norm(old_force), 0.1 * mu_n);
  // Rotate the normal by 0.1 rad about an axis in the old plane, with no slip.
  const double phi = 0.1;
  Vec3 normal{std::sin(phi), 0.0, std::cos(phi)};
  const ContactForce f = tangential_step(p, s, {}, normal);
  const Vec3 expected = old_force - dot(old_force, normal) * normal;
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(f.tangential[a], expected[a], 1e-14 * mu_n);
  EXPECT_NEAR(dot(f.tangential, normal), 0.0, 1e-15 * mu_n);
  // Keep rotating the normal about y and slipping in the current plane: the force stays in it.
  for (int k = 1; k <= 200; ++k) {
    const double angle = phi + 0.01 * k;
    normal = {std::sin(angle), 0.0, std::cos(angle)};
    const Vec3 slip = cross(normal, Vec3{0.0, 1.0, 0.0}) * (0.01 * s_star) + Vec3{0.0, 1e-3 * s_star, 0.0};
    const ContactForce g = tangential_step(p, s, slip, normal);
    ASSERT_NEAR(dot(g.tangential, normal), 0.0, 1e-14 * mu_n) << "step " << k;
    ASSERT_LE(norm(g.tangential), mu_n * (1.0 + 1e-14));
  }
}

// The Coulomb limit follows the current normal force: while the normal spring unloads on K2 the
// stored tangential force is cut to mu N (T = min(|tf|, mu N) of eq. 2-4-21), keeps its
// direction, and vanishes once N = 0 below alpha0 (no friction without contact force).
TEST(WaltonBraun, TangentialForceFollowsFallingNormalForce) {
  const auto p = WaltonBraun::make(kK1, kE, kRatk, kMu);
  WaltonBraun::State s;
  const double mu_n = kMu * kK1 * kOverlap;
  const double ds = 1.5 * mu_n / p.k0 / 1000.0;
  for (int k = 0; k < 700; ++k) tangential_step(p, s, {ds, 0.0, 0.0});  // T = (1 - 0.3^1.5) mu N
  ASSERT_GT(-s.tangential_force.x, 0.8 * mu_n);
  double previous = -s.tangential_force.x;
  ContactKinematics c;
  c.normal = {0.0, 0.0, 1.0};
  c.slip_velocity = {0.1 * ds, 0.0, 0.0};
  c.effective_mass = 1.0e-5;
  for (int k = 1; k <= 40; ++k) {
    c.overlap = kOverlap * (1.0 - 0.01 * k);  // alpha0 = 0.75 alpha_max: N reaches 0 at k = 25
    const ContactForce f = WaltonBraun::force(p, s, c, 1.0);
    const double limit = kMu * f.normal;
    EXPECT_LE(norm(f.tangential), limit * (1.0 + 1e-14) + 1e-300) << "step " << k;
    EXPECT_EQ(f.tangential.y, 0.0);
    EXPECT_EQ(f.tangential.z, 0.0);
    if (f.normal > 0.0 && limit < previous) {
      EXPECT_NEAR(-f.tangential.x, limit, 1e-12 * mu_n) << "should slide on the shrinking limit, step " << k;
    } else if (f.normal == 0.0) {
      EXPECT_EQ(norm(f.tangential), 0.0) << "friction without normal force at step " << k;
    }
    previous = -f.tangential.x;
  }
}

// ---------------------------------------------------------------------------------------------
// Engine level: the residual overlap alpha0 of one contact must not survive separation. The engine
// resets the law's State when a pair (or particle-wall pair) starts touching again. Were alpha0 kept,
// a second, slower impact with alpha_max < alpha0 of the first would feel no force up to alpha0
// and then bounce elastically on K2 (e -> 1 instead of 0.5).
// ---------------------------------------------------------------------------------------------
namespace {

// The engine for d = 2 mm glass, K1 = 1e4 N/m, e = 0.5 for pairs and the wall, 50 steps per eq. (2-5-4).
DemEngineVariant residual_engine(const std::string& csv, const std::string& y_boundary) {
  const std::string text = R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.02, 0.02]
boundary = { x = "periodic", y = )" +
                           y_boundary + R"(, z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
[particles]
init = "file"
file = ")" + csv + R"("
[contact]
model = "walton_braun"
k1 = 1.0e4
restitution = 0.5
[run]
duration = 1.0
collision_steps = 50
)";
  return test::engine_from_toml(text, testing::TempDir() + "residual.toml", 1);
}

}  // namespace

TEST(WaltonBraun, EngineResetsResidualOverlapBetweenWallImpacts) {
  const double v1 = 0.5;  // m/s, first impact; the second is at 0.3 v1 < (alpha0 / alpha_max1 = 0.75) v1
  const test::ParticleFile csv("residual_wall.csv", "glass,0.01,0.0010001,0.01,0.0,-0.5,0.0\n");
  auto engine = residual_engine(csv.path(), R"(["wall", "open"])");
  std::visit(
      [&](auto& e) {
        auto& p = e.state().particles;
        const double r = p.radius[0];
        auto bounce = [&](double speed_in) {
          p.velocity[0] = {0.0, -speed_in, 0.0};
          bool touched = false;
          for (int k = 0; k < 100000; ++k) {
            e.step();
            const bool touching = p.position[0].y < r;
            touched = touched || touching;
            if (touched && !touching) break;
          }
          EXPECT_TRUE(touched);
          return p.velocity[0].y / speed_in;
        };
        // 50 steps per eq. (2-5-4) (about 70 per wall contact): Verlet's error in e is ~(pi/70)^2/2 ~
        // 0.1%; 1% as in the head-on test.
        EXPECT_NEAR(bounce(v1), 0.5, 0.005);
        // Move away a little, then come back slower. The wall's memory must have been reset.
        for (int k = 0; k < 10; ++k) e.step();
        EXPECT_NEAR(bounce(0.3 * v1), 0.5, 0.005) << "stale residual overlap from the first impact";
      },
      engine);
}

TEST(WaltonBraun, EngineResetsResidualOverlapBetweenPairImpacts) {
  // Two spheres approach head-on at 0.25 m/s each, separate, and are sent back at 0.3 x that.
  const test::ParticleFile csv("residual_pair.csv",
                               "glass,0.008,0.01,0.01,0.25,0.0,0.0\n"
                               "glass,0.0100001,0.01,0.01,-0.25,0.0,0.0\n");
  auto engine = residual_engine(csv.path(), R"("periodic")");
  std::visit(
      [&](auto& e) {
        auto& p = e.state().particles;
        auto gap = [&] { return std::fabs(p.position[1].x - p.position[0].x) - (p.radius[0] + p.radius[1]); };
        auto collide = [&](double speed_each) {
          // Indices may be re-sorted at a rebuild: find who is on the left.
          const std::size_t left = p.position[0].x < p.position[1].x ? 0 : 1;
          p.velocity[left] = {speed_each, 0.0, 0.0};
          p.velocity[1 - left] = {-speed_each, 0.0, 0.0};
          bool touched = false;
          for (int k = 0; k < 100000; ++k) {
            e.step();
            touched = touched || gap() < 0.0;
            if (touched && gap() > 0.0) break;
          }
          EXPECT_TRUE(touched);
          return (p.velocity[1 - left].x - p.velocity[left].x) / (2.0 * speed_each);
        };
        const long rebuilds = e.statistics().rebuilds;
        EXPECT_NEAR(collide(0.25), 0.5, 0.005);  // same tolerance as the wall test
        for (int k = 0; k < 10; ++k) e.step();
        EXPECT_NEAR(collide(0.3 * 0.25), 0.5, 0.005) << "stale residual overlap from the first impact";
        // No neighbor-list rebuild happened, so the reset came from the touching flag itself.
        EXPECT_EQ(e.statistics().rebuilds, rebuilds);
      },
      engine);
}
