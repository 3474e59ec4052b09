// Free flight of the event-driven engine (src/grainflow/edmd/free_flight.hpp): the contact time of
// two spheres (the quadratic of Campbell 1982 section 2.9), the closing time of a centre on a plane
// under gravity (walls, cell faces), and the contact time with a relative acceleration (the quartic
// of a particle rolling on a wall against a free one, section 2.14.2).
//
// References are computed independently in long double (x86-64: 64-bit significand, eps 5.4e-20,
// 2^11 times finer than double), from the textbook root formula and Newton polishing, or by a brute
// scan of the polynomial; inputs are chosen exactly representable where the test is about
// round-off, so that the only error measured is the solver's own.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

#include "grainflow/edmd/free_flight.hpp"

using namespace grainflow;
using namespace grainflow::edmd;

namespace {

using ld = long double;
constexpr double kEps = DBL_EPSILON;  // 2.2e-16

// The smaller root of a t^2 + 2 b t + c = 0 (|dr + dv t|^2 = sigma^2), in long double, polished by
// two Newton steps on the quadratic: accurate to ~1e-19 relative wherever the root is simple.
ld reference_contact_time(const Vec3& dr, const Vec3& dv, double sigma) {
  const ld a = (ld)dv.x * dv.x + (ld)dv.y * dv.y + (ld)dv.z * dv.z;
  const ld b = (ld)dr.x * dv.x + (ld)dr.y * dv.y + (ld)dr.z * dv.z;
  const ld c = (ld)dr.x * dr.x + (ld)dr.y * dr.y + (ld)dr.z * dr.z - (ld)sigma * sigma;
  const ld disc = b * b - a * c;
  ld t = c / (-b + std::sqrt(disc));
  for (int k = 0; k < 2; ++k) t -= (a * t * t + 2 * b * t + c) / (2 * (a * t + b));
  return t;
}

// The same root by the textbook formula (-b - sqrt(b^2 - a c)) / a in double: what Campbell's
// section 2.14.1 warns loses precision when b^2 >> a c. Used to show the cases below would catch it.
double naive_contact_time(const Vec3& dr, const Vec3& dv, double sigma) {
  const double a = norm2(dv), b = dot(dr, dv), c = norm2(dr) - sigma * sigma;
  return (-b - std::sqrt(b * b - a * c)) / a;
}

double relative_error(double t, ld reference) { return (double)std::fabs(((ld)t - reference) / reference); }

// ---------------------------------------------------------------------------------------------
// contact_time

TEST(ContactTime, HeadOnMatchesExactRoot) {
  // Centres 3 apart closing at 2 along x, sigma = 1: contact after (3 - 1) / 2 = 1 exactly.
  EXPECT_EQ(contact_time({3, 0, 0}, {-2, 0, 0}, 1.0), 1.0);
  // Oblique: dr = (5, 0.6), dv = (-1, 0), sigma = 1: contact when x = sqrt(1 - 0.36) = 0.8, t = 4.2.
  EXPECT_NEAR(contact_time({5, 0.6, 0}, {-1, 0, 0}, 1.0), 4.2, 4 * kEps * 4.2);
}

// Forward error bound of the double-precision contact time from rounding its inputs' dot
// products: a, b, c are each computed to ~2 eps of the sum of the magnitudes of their terms, and
// the root of a t^2 + 2 b t + c moves by dt/dc = 1/(2 sqrt(disc)), dt/db = t/sqrt(disc),
// dt/da = t^2/(2 sqrt(disc)). Relative to t, plus a few ulps for the solve itself.
double contact_time_error_bound(const Vec3& dr, const Vec3& dv, double sigma, double t) {
  const double disc = dot(dr, dv) * dot(dr, dv) - norm2(dv) * (norm2(dr) - sigma * sigma);
  const double root = std::sqrt(disc);
  const double dc = 2 * kEps * (norm2(dr) + sigma * sigma), db = 2 * kEps * norm(dr) * norm(dv),
               da = 2 * kEps * norm2(dv);
  return 4.0 * (dc / (2 * root) + db * t / root + da * t * t / (2 * root)) / t + 8 * kEps;
}

TEST(ContactTime, RandomCasesMatchLongDoubleRoot) {
  // 10^5 random approaching pairs, speeds and sizes over 12 and 4 decades, paths not near-grazing
  // (discriminant > 1e-2 b^2; grazing is tested below). The error allowed is the forward bound
  // from rounding the inputs (contact_time_error_bound: the conditioning of the problem, ~1e-15 for
  // most cases, up to ~1e-13 when the gap is a small fraction of |dr|^2); the stable formula meets
  // it, while a cancelling formula would exceed it whenever b^2 >> a c.
  std::mt19937_64 rng(20240301);
  std::uniform_real_distribution<double> u(-1.0, 1.0), scale(-6.0, 6.0);
  int tested = 0;
  double worst = 0.0;  // error / bound
  while (tested < 100000) {
    const double sigma = std::pow(10.0, 0.3 * scale(rng));
    const Vec3 dr = Vec3{u(rng), u(rng), u(rng)} * (4.0 * sigma);
    const Vec3 dv = Vec3{u(rng), u(rng), u(rng)} * std::pow(10.0, scale(rng));
    const double b = dot(dr, dv), a = norm2(dv), c = norm2(dr) - sigma * sigma;
    if (b >= 0.0 || c <= 0.01 * sigma * sigma || b * b - a * c < 1e-2 * b * b) continue;
    ++tested;
    const double t = contact_time(dr, dv, sigma);
    ASSERT_TRUE(std::isfinite(t)) << "missed a collision";
    const double error = relative_error(t, reference_contact_time(dr, dv, sigma));
    worst = std::max(worst, error / contact_time_error_bound(dr, dv, sigma, t));
  }
  EXPECT_LT(worst, 1.0);
}

TEST(ContactTime, LargeBNoCancellation) {
  // b^2 >> a c: a gap of 2^-26 sigma closed at unit speed along the centre line, with a small
  // tangential speed. dr.x = 1 + 2^-26 makes |dr|^2 - sigma^2 = 2^-25 + 2^-52 exact in double, so
  // the inputs carry no rounding; the exact root is ~1.5e-8. The textbook formula subtracts two
  // numbers ~1 to get it and keeps only ~8 digits; the stable formula has no subtraction and must
  // be good to a few ulps (1e-15 relative).
  const double gap = std::ldexp(1.0, -26);
  for (const Vec3 dv : {Vec3{-1, 0.25, 0}, Vec3{-0.5, 0.5, -0.25}, Vec3{-3, 1, 0}, Vec3{-7, -5, 3}}) {
    const Vec3 dr{1.0 + gap, 0, 0};
    const ld ref = reference_contact_time(dr, dv, 1.0);
    const double t = contact_time(dr, dv, 1.0);
    EXPECT_LT(relative_error(t, ref), 1e-15) << "dv.x = " << dv.x;
    // The test discriminates: the cancelling formula is off by 5e-10 to 2e-9 here.
    EXPECT_GT(relative_error(naive_contact_time(dr, dv, 1.0), ref), 1e-12) << "dv.x = " << dv.x;
  }
  // Very fast approach from far away: a/c tiny relative to b^2/c: still to a few ulps.
  const Vec3 dr{1.0 + std::ldexp(1.0, -20), 0.0, 0.0}, dv{-1e8, 1.0, 0.0};
  EXPECT_LT(relative_error(contact_time(dr, dv, 1.0), reference_contact_time(dr, dv, 1.0)), 1e-15);
}

TEST(ContactTime, NearGrazing) {
  // dr = (0.5, h), dv = (-1, 0), sigma = 1: the paths touch only if h < 1, at t = 0.5 - sqrt(1 - h^2).
  // h = 1 - 2^-26 misses head-on by 1.5e-8 sigma; h^2 = 1 - 2^-25 + 2^-52 and everything after is
  // exact in double, so the discriminant 2^-25 - 2^-52 is exact and t must be right to a few ulps.
  {
    const double h = 1.0 - std::ldexp(1.0, -26);
    const ld exact = 0.5L - std::sqrt(1.0L - (ld)h * h);
    EXPECT_LT(relative_error(contact_time({0.5, h, 0}, {-1, 0, 0}, 1.0), exact), 1e-15);
  }
  // Just outside (h = 1 + 2^-26): the paths miss, however slightly.
  EXPECT_EQ(contact_time({0.5, 1.0 + std::ldexp(1.0, -26), 0}, {-1, 0, 0}, 1.0), kNever);
  // Exactly tangent (discriminant 0): a touch without approach is no collision.
  EXPECT_EQ(contact_time({0.5, 1.0, 0}, {-1, 0, 0}, 1.0), kNever);
  // Random near-grazing: miss distance h = sigma (1 - delta), delta from 1e-12 to 1e-3. Near a double
  // root the root's relative condition number in the discriminant is ~ b^2 / disc ~ 1 / delta, and
  // the inputs (rotated, not exact) carry ~eps rounding: allow 1e-14 / delta relative, and check
  // that the root is a true contact: |dr + dv t| = sigma to 1e-14 relative (the distance is well
  // conditioned even where t is not).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), logdelta(-12.0, -3.0), angle(0.0, 2.0 * M_PI);
  for (int k = 0; k < 20000; ++k) {
    const double delta = std::pow(10.0, logdelta(rng)), phi = angle(rng), sigma = 1.0 + 0.5 * u(rng);
    const double h = sigma * (1.0 - delta), x0 = 3.0 * sigma, speed = std::pow(10.0, 3.0 * u(rng));
    const Vec3 dr{x0 * std::cos(phi) - h * std::sin(phi), x0 * std::sin(phi) + h * std::cos(phi), 0.0};
    const Vec3 dv{-speed * std::cos(phi), -speed * std::sin(phi), 0.0};
    const double t = contact_time(dr, dv, sigma);
    ASSERT_TRUE(std::isfinite(t)) << "missed a grazing collision, delta = " << delta;
    const ld ref = reference_contact_time(dr, dv, sigma);
    EXPECT_LT(relative_error(t, ref), 1e-14 / delta) << "delta = " << delta;
    EXPECT_NEAR(norm(dr + t * dv) / sigma, 1.0, 1e-14) << "delta = " << delta;
  }
}

TEST(ContactTime, OverlappingAndRecedingCases) {
  // Overlapping by round-off and approaching: collide now (t = 0), never a pass-through.
  EXPECT_EQ(contact_time({1.0 - 1e-15, 0, 0}, {-1, 0, 0}, 1.0), 0.0);
  EXPECT_EQ(contact_time({0.5, 0.1, 0}, {-1, 0.3, 0}, 1.0), 0.0);  // deep overlap, approaching
  EXPECT_EQ(contact_time({1.0, 0, 0}, {-1, 0, 0}, 1.0), 0.0);      // exactly touching, approaching
  // Receding: never, whether apart, touching or overlapping (separating particles are left alone).
  EXPECT_EQ(contact_time({3, 0, 0}, {1, 0, 0}, 1.0), kNever);
  EXPECT_EQ(contact_time({1.0, 0, 0}, {1e-300, 0, 0}, 1.0), kNever);
  EXPECT_EQ(contact_time({1.0 - 1e-15, 0, 0}, {1, 0, 0}, 1.0), kNever);
  EXPECT_EQ(contact_time({0.5, 0, 0}, {0, 1, 0}, 1.0), kNever);  // overlapping, b = 0
  // Parallel motion (b = 0) and no relative motion at all: never.
  EXPECT_EQ(contact_time({3, 0, 0}, {0, 1, 0}, 1.0), kNever);
  EXPECT_EQ(contact_time({3, 0, 0}, {0, 0, 0}, 1.0), kNever);
  // Touching while sliding past (normal approach below 1e-9 of the relative speed: a grazing
  // contact whose sign is round-off) or approaching slower than the caller's speed floor (the
  // engine passes 1e-10 of the particles' speeds): no impulse worth resolving, never.
  EXPECT_EQ(contact_time({1.0 - 1e-15, 0, 0}, {-1e-12, 1.0, 0}, 1.0), kNever);
  EXPECT_EQ(contact_time({1.0 - 1e-15, 0, 0}, {-1e-6, 1.0, 0}, 1.0), 0.0);
  EXPECT_EQ(contact_time({1.0 - 1e-15, 0, 0}, {-1e-6, 0, 0}, 1.0, 2e-6), kNever);
  EXPECT_EQ(contact_time({1.0 - 1e-15, 0, 0}, {-1e-6, 0, 0}, 1.0, 5e-7), 0.0);
  // Random receding pairs (b > 0), overlapping or not: never.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 10000; ++k) {
    const Vec3 dr{u(rng), u(rng), u(rng)}, dv{u(rng), u(rng), u(rng)};
    const double sigma = 0.3 + std::fabs(u(rng));
    const double t = contact_time(dr, dv, sigma);
    if (dot(dr, dv) > 0.0) {
      EXPECT_EQ(t, kNever);
    } else if (norm2(dr) <= sigma * sigma) {
      EXPECT_EQ(t, 0.0);  // overlapping and approaching
    } else {
      EXPECT_GE(t, 0.0);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// closing_time(gap, rate, accel): first t >= 0 with gap + rate t + accel t^2 / 2 = 0, closing.

// The closing root in long double from the two roots of the quadratic (both computed stably).
ld reference_closing_time(ld gap, ld rate, ld accel) {
  if (accel == 0) return rate < 0 ? gap / -rate : (ld)INFINITY;
  const ld disc = rate * rate - 2 * accel * gap;
  if (disc < 0) return INFINITY;
  const ld q = -0.5L * (rate + std::copysign(std::sqrt(disc), rate));
  ld best = INFINITY;
  for (ld t : {q / (0.5L * accel), gap / q})
    if (t >= 0 && rate + accel * t < 0) best = std::min(best, t);
  return best;
}

TEST(ClosingTime, ConstantSpeed) {
  EXPECT_EQ(closing_time(2.0, -4.0, 0.0), 0.5);
  EXPECT_EQ(closing_time(2.0, 4.0, 0.0), kNever);  // moving away
  EXPECT_EQ(closing_time(2.0, 0.0, 0.0), kNever);  // at rest
}

TEST(ClosingTime, FallingOntoAFloor) {
  // A centre h = 2 above the plane moving up at v = 3 under g = 9.81 (gap acceleration -g):
  // it rises, turns and comes back: t = (v + sqrt(v^2 + 2 g h)) / g. Few-ulp accuracy: 4 eps.
  const double g = 9.81, h = 2.0, v = 3.0;
  const double exact = (v + std::sqrt(v * v + 2 * g * h)) / g;
  EXPECT_NEAR(closing_time(h, v, -g), exact, 4 * kEps * exact);
  // Dropped from rest: sqrt(2 h / g).
  EXPECT_NEAR(closing_time(h, 0.0, -g), std::sqrt(2 * h / g), 4 * kEps);
  // Moving down: (-v + sqrt(v^2 + 2 g h)) / g computed without cancellation when v^2 >> g h:
  // gap 1e-12 at 1e3 m/s: t ~ 1e-15 s, which the stable form keeps to a few ulps.
  const double t = closing_time(1e-12, -1e3, -g);
  EXPECT_LT(relative_error(t, reference_closing_time(1e-12L, -1e3L, -(ld)g)), 1e-15);
}

TEST(ClosingTime, ReturningParabolaAndTurningBeforeThePlane) {
  // A cell face above a particle moving toward it (gap 0.4 closing at 1) while gravity pulls it back
  // (gap acceleration +1): reaches it at t = 1 - sqrt(0.2), the first root; the second root
  // (1 + sqrt(0.2)) is the way back out and must not be taken.
  EXPECT_NEAR(closing_time(0.4, -1.0, 1.0), 1.0 - std::sqrt(0.2), 4 * kEps);
  // Gap 1: it turns 0.5 short of the face: never.
  EXPECT_EQ(closing_time(1.0, -1.0, 1.0), kNever);
  // Exactly grazing the face at the apex (disc = 0): no crossing.
  EXPECT_EQ(closing_time(0.5, -1.0, 1.0), kNever);
  // Receding with gravity pointing away (gap accelerates open): never.
  EXPECT_EQ(closing_time(1.0, 1.0, 1.0), kNever);
}

TEST(ClosingTime, AtOrBeyondThePlane) {
  // On or (by round-off) beyond the plane and closing: now.
  EXPECT_EQ(closing_time(0.0, -1.0, 0.0), 0.0);
  EXPECT_EQ(closing_time(-1e-15, -1.0, -9.81), 0.0);
  EXPECT_EQ(closing_time(-1e-15, -1.0, 9.81), 0.0);
  EXPECT_EQ(closing_time(0.0, 0.0, -9.81), 0.0);  // resting on it with gravity pressing
  // Beyond by round-off but receding, under gravity that brings it back: the next closing is when
  // the parabola returns, t = 2 v / g (the root of v t - g t^2 / 2 other than 0), not 0 (which
  // would repeat the bounce forever) and not never (which would lose the wall).
  for (double beyond : {0.0, -1e-15, -1e-12}) {
    EXPECT_NEAR(closing_time(beyond, 0.5, -9.81), 2 * 0.5 / 9.81, 4 * kEps) << beyond;
    EXPECT_EQ(closing_time(beyond, 0.5, 0.0), kNever) << beyond;
    EXPECT_EQ(closing_time(beyond, 0.5, 9.81), kNever) << beyond;
  }
  EXPECT_EQ(closing_time(0.0, 0.0, 9.81), kNever);  // at rest, accelerating away
}

TEST(ClosingTime, RandomCasesMatchLongDouble) {
  // Random gaps, rates and accelerations over many decades; the result must be the smallest closing
  // root to 1e-13 relative. The roots are computed stably in both; the only ill conditioning is
  // near a double root (disc -> 0), excluded here (disc > 1e-6 rate^2) and covered above.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0), decade(-6.0, 6.0);
  int finite = 0;
  for (int k = 0; k < 100000; ++k) {
    const double gap = std::pow(10.0, decade(rng)) * (u(rng) > -0.9 ? 1.0 : 0.0);
    const double rate = std::pow(10.0, decade(rng)) * u(rng), accel = std::pow(10.0, decade(rng)) * u(rng);
    const double disc = rate * rate - 2 * accel * gap;
    if (disc >= 0.0 && disc < 1e-6 * rate * rate) continue;
    const double t = closing_time(gap, rate, accel);
    const ld ref = gap == 0.0 && rate > 0.0 && accel < 0.0 ? -2.0L * rate / accel
                   : gap == 0.0 && (rate < 0.0 || (rate == 0.0 && accel < 0.0))
                       ? 0.0L
                       : reference_closing_time(gap, rate, accel);
    if (std::isinf((double)ref)) {
      EXPECT_EQ(t, kNever) << gap << ' ' << rate << ' ' << accel;
      continue;
    }
    ++finite;
    if (ref == 0) EXPECT_EQ(t, 0.0);
    else EXPECT_LT(relative_error(t, ref), 1e-13) << gap << ' ' << rate << ' ' << accel;
    // The position at t is on the plane and closing.
    EXPECT_LT(rate + accel * t, 0.0);
  }
  EXPECT_GT(finite, 30000);  // both branches exercised
}

// ---------------------------------------------------------------------------------------------
// contact_time_accelerated: |dr + dv t + da t^2 / 2| = sigma, first closing root in [0, horizon).

struct Quartic {
  ld c4, c3, c2, c1, c0;
  Quartic(const Vec3& dr, const Vec3& dv, const Vec3& da, double sigma) {
    auto d = [](const Vec3& a, const Vec3& b) { return (ld)a.x * b.x + (ld)a.y * b.y + (ld)a.z * b.z; };
    c4 = 0.25L * d(da, da);
    c3 = d(dv, da);
    c2 = d(dv, dv) + d(dr, da);
    c1 = 2 * d(dr, dv);
    c0 = d(dr, dr) - (ld)sigma * sigma;
  }
  ld operator()(ld t) const { return (((c4 * t + c3) * t + c2) * t + c1) * t + c0; }
  ld derivative(ld t) const { return ((4 * c4 * t + 3 * c3) * t + 2 * c2) * t + c1; }
  // Bound on the time error of a root t found by bisecting f evaluated in double: the bisection
  // stops at 1e-15 (1 + t); f's coefficients and Horner sums carry ~eps times the sum of the
  // magnitudes of their terms (x 8 for the few operations), which moves the zero of f by that over
  // |f'(t)|. Large when the root is nearly a double root (grazing): then the time is ill
  // conditioned although the contact distance is not.
  double time_tolerance(double t) const {
    const ld T = std::fabs((ld)t);
    const ld terms = std::fabs(c4) * T * T * T * T + std::fabs(c3) * T * T * T + std::fabs(c2) * T * T +
                     std::fabs(c1) * T + std::fabs(c0) + 1.0L;
    return 1e-15 * (1.0 + t) + (double)(8 * kEps * terms / std::fabs(derivative(t)));
  }
};

ld distance_at(const Vec3& dr, const Vec3& dv, const Vec3& da, ld t) {
  ld s = 0;
  for (int a = 0; a < 3; ++a) {
    const ld x = (ld)dr[a] + (ld)dv[a] * t + 0.5L * (ld)da[a] * t * t;
    s += x * x;
  }
  return std::sqrt(s);
}

TEST(ContactTimeAccelerated, ReducesToTheQuadraticWithoutAcceleration) {
  // With da = 0 the quartic is the quadratic of contact_time: same root within the bisection's and
  // the quartic evaluation's error (Quartic::time_tolerance), or both none.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0;
  for (int k = 0; k < 5000; ++k) {
    const Vec3 dr = Vec3{u(rng), u(rng), u(rng)} * 5.0;
    if (norm2(dr) <= 1.0) continue;
    const Vec3 dv = dr * (-0.3 * (1.0 + u(rng))) + Vec3{u(rng), u(rng), u(rng)};  // mostly approaching
    const double quadratic = contact_time(dr, dv, 1.0);
    const double quartic = contact_time_accelerated(dr, dv, {}, 1.0, kNever);
    if (quadratic == kNever) {
      // A miss by the quadratic may be found by bisection only as a touch within round-off.
      if (quartic != kNever) {
        EXPECT_NEAR((double)distance_at(dr, dv, {}, quartic), 1.0, 1e-7);
      }
      continue;
    }
    ++hits;
    ASSERT_NE(quartic, kNever) << "missed a collision (case " << k << ")";
    EXPECT_NEAR(quartic, quadratic, Quartic(dr, dv, {}, 1.0).time_tolerance(quadratic)) << k;
  }
  EXPECT_GT(hits, 500);
}

TEST(ContactTimeAccelerated, OverlapAndRecedingCases) {
  const Vec3 g{0.0, -1.0, 0.0};
  EXPECT_EQ(contact_time_accelerated({0.9, 0, 0}, {-1, 0, 0}, g, 1.0, kNever), 0.0);    // overlapping, closing
  EXPECT_EQ(contact_time_accelerated({0.9, 0, 0}, {1, 0, 0}, g, 1.0, kNever), kNever);  // overlapping, opening
  // Apart and moving away, but the acceleration brings them back: found (x = 2 + t - t^2/2 = 1
  // at t = 1 + sqrt(3)).
  EXPECT_NEAR(contact_time_accelerated({2, 0, 0}, {1, 0, 0}, {-1, 0, 0}, 1.0, kNever), 1.0 + std::sqrt(3.0), 1e-14);
  // The same beyond the horizon: not reported.
  EXPECT_EQ(contact_time_accelerated({2, 0, 0}, {1, 0, 0}, {-1, 0, 0}, 1.0, 2.0), kNever);
  // Accelerating apart for good: never.
  EXPECT_EQ(contact_time_accelerated({2, 0, 0}, {1, 0, 0}, {1, 0, 0}, 1.0, kNever), kNever);
}

TEST(ContactTimeAccelerated, TouchingAndRecedingButAcceleratedBack) {
  // The quartic's counterpart of ClosingTime.AtOrBeyondThePlane: a pair touching (by round-off
  // just overlapping) and separating, whose relative acceleration brings it back, collides again
  // when the motion returns: x(t) = 1 + 0.5 t - t^2 / 2 is back at sigma = 1 at t = 1. (A free
  // disc bouncing off one rolling on the floor, with gravity acting on the free one only, is this
  // case; answering never lets gravity press the free disc into the rolling one.)
  for (double x0 : {1.0, 1.0 - 1e-15}) {
    const double t = contact_time_accelerated({x0, 0, 0}, {0.5, 0, 0}, {-1, 0, 0}, 1.0, kNever);
    EXPECT_NEAR(t, 1.0, 1e-9) << "x0 = 1 - " << 1.0 - x0;
  }
  // Oblique, as when the upper disc slides over the lower one: normal speed +1e-9 (separating),
  // tangential 0.5, gravity on the upper disc only (relative acceleration (0, +1) from the upper to
  // the lower disc). dr points from the lower (rolling) to the upper disc; it returns after ~2e-9.
  const Vec3 n = Vec3{0.6, 0.8, 0.0};
  const Vec3 tangent{-0.8, 0.6, 0.0};
  const double t = contact_time_accelerated(n * (1.0 - 1e-16), 1e-9 * n + 0.5 * tangent, {0.0, -1.0, 0.0}, 1.0, kNever);
  EXPECT_LT(t, 1e-6) << "the pressing pair is never predicted to touch again";
}

TEST(ContactTimeAccelerated, FindsANarrowFirstDipBeforeTheReturn) {
  // Along x: x(t) = -5 + 4 t - t^2 / 2 (decelerating, turns at t = 4, x = 3), at y = 1 - eps.
  // With sigma = 1 the path cuts the sphere in a chord |x| < w = sqrt(2 eps - eps^2) on the way
  // out, and again on the way back (t ~ 6.4): the first root is where x = -w (t ~ 1.55). For eps = 1e-8 the chord
  // is 2.8e-4 long and f dips only 2e-8 below zero: a scan of 1000 steps misses it; the monotonic
  // splitting at the roots of f' and f'' must not. Root from x(t) = -w in long double.
  for (double eps : {1e-4, 1e-8}) {
    const double y = 1.0 - eps;
    const Vec3 dr{-5.0, y, 0.0}, dv{4.0, 0.0, 0.0}, da{-1.0, 0.0, 0.0};
    const ld w = std::sqrt(1.0L - (ld)y * y);
    // -5 + 4 t - t^2/2 + w = 0  ->  t = 4 - sqrt(16 - 2 (5 - w))
    const ld exact = 4.0L - std::sqrt(16.0L - 2.0L * (5.0L - w));
    const double t = contact_time_accelerated(dr, dv, da, 1.0, kNever);
    // Tolerance: bisection plus quartic evaluation error over |f'| (~4e-10 for eps = 1e-8, where
    // |f'| = 2 w |x'| is only 7e-4); the contact distance itself must be right to 1e-14.
    EXPECT_NEAR(t, (double)exact, Quartic(dr, dv, da, 1.0).time_tolerance(t)) << "eps = " << eps;
    EXPECT_NEAR((double)distance_at(dr, dv, da, t), 1.0, 1e-14) << "eps = " << eps;
    EXPECT_LT(t, 2.0);  // the first root, not the one on the way back (t ~ 6.4)
  }
}

TEST(ContactTimeAccelerated, RandomCasesAgainstABruteForceScan) {
  // Random relative motions with accelerations (rolling vs free particles: da ~ g), sigma = 1.
  // Reference: scan f(t) = |dr + dv t + da t^2/2|^2 - 1 in long double over [0, T] with 20000 steps,
  // take the first step where it falls through zero, and bisect that step to 1e-18. Checks:
  //  - never a missed first root: the solver's root is not later than the scan's (1e-12 slack),
  //  - a reported root is a true contact: |distance - 1| < 1e-12 at the root, and the distance is
  //    non-increasing through it (closing);
  //  - if the scan finds no crossing, the solver's root (if any) must be a real narrow dip: the
  //    distance dips below 1 just after it.
  // The solver bisects to ~1e-15 (1 + t) in t; distance errors are then ~|d'| 1e-15 T: 1e-12 is a
  // generous bound for |d'| <= ~30, T <= 10.
  std::mt19937_64 rng(1982);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int steps = 20000;
  int hits = 0, dips_missed_by_scan = 0;
  for (int k = 0; k < 5000; ++k) {
    Vec3 dr{4.0 * u(rng), 4.0 * u(rng), k % 2 ? 0.0 : 4.0 * u(rng)};
    if (norm(dr) <= 1.0) continue;
    const Vec3 dv = dr * (-0.25 * (1.0 + u(rng))) + Vec3{u(rng), u(rng), k % 2 ? 0.0 : u(rng)} * 2.0;
    const Vec3 da = Vec3{u(rng), u(rng), k % 2 ? 0.0 : u(rng)} * 2.0;
    const double horizon = 10.0;
    const Quartic f(dr, dv, da, 1.0);
    ld scan = INFINITY;
    for (int s = 0; s < steps; ++s) {
      ld lo = horizon * (ld)s / steps, hi = horizon * (ld)(s + 1) / steps;
      if (f(lo) > 0 && f(hi) <= 0) {
        for (int it = 0; it < 80; ++it) {
          const ld mid = 0.5L * (lo + hi);
          (f(mid) > 0 ? lo : hi) = mid;
        }
        scan = lo;
        break;
      }
    }
    const double t = contact_time_accelerated(dr, dv, da, 1.0, horizon);
    if (std::isinf((double)scan)) {
      if (t != kNever) {  // only acceptable as a dip narrower than the scan's step
        ++dips_missed_by_scan;
        EXPECT_NEAR((double)distance_at(dr, dv, da, t), 1.0, 1e-12) << k;
        EXPECT_LT(distance_at(dr, dv, da, t + 1e-9), 1.0L) << k;
      }
      continue;
    }
    ++hits;
    ASSERT_NE(t, kNever) << "missed a collision at t = " << (double)scan << " (case " << k << ")";
    EXPECT_LE(t, (double)scan + 1e-12) << "missed an earlier root (case " << k << ")";
    EXPECT_NEAR((double)distance_at(dr, dv, da, t), 1.0, 1e-12) << k;
    EXPECT_LE(distance_at(dr, dv, da, t + 1e-9), distance_at(dr, dv, da, t)) << k;
    if (t < (double)scan - 1e-12) ++dips_missed_by_scan;  // solver found a dip the scan stepped over
  }
  EXPECT_GT(hits, 500);
  // The scan's step (5e-4) is coarse only for dips shallower than ~1e-7: rare among random cases.
  EXPECT_LT(dips_missed_by_scan, 10);
}

}  // namespace
