// Exact free flight between events (parabolic under gravity) and the roots that schedule events:
// when two spheres touch (the quadratic of Campbell 1982 section 2.9, solved without cancellation),
// when a centre reaches a plane moving at constant speed (walls, cell faces).
#pragma once

#include <cmath>
#include <algorithm>
#include <limits>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow::edmd {

inline constexpr double kNever = std::numeric_limits<double>::infinity();

// Relative speeds below this fraction of the particles' speeds are round-off (see approaching()).
inline constexpr double kVelocityResolution = 1e-10;

// True when two touching particles close in faster than round-off resolves: the normal relative
// speed must exceed 1e-9 of the relative speed (else the contact is grazing) and `speed_floor`
// (the engine passes 1e-10 of the particles' speeds: below it an impulse is lost in the rounding
// of their velocities). Such contacts exchange no momentum worth resolving; skipping them stops
// endless zero-impulse "collisions" of neighbours sliding together at one instant.
inline bool approaching(const Vec3& dr, const Vec3& dv, double speed_floor = 0.0) {
  constexpr double kGrazing = 1e-9;
  const double distance = std::sqrt(norm2(dr));
  return dot(dr, dv) < -distance * std::max(kGrazing * std::sqrt(norm2(dv)), speed_floor);
}

// Time until |dr + dv t| = sigma for approaching spheres, if that is before `horizon` (the best
// event found so far; kNever: any time); 0 if they already overlap while approaching (round-off),
// kNever if they miss, separate, or meet only at or after the horizon. Relative motion is linear:
// gravity accelerates both alike. Uses t = c / (-b + sqrt(b^2 - a c)), which has no cancellation.
// Past the horizon is decided without the square root where t >= c / (-2b) (the root's denominator
// is at most -2b) is already beyond it, with a 1e-9 margin so no earlier root is dropped by
// rounding. The speed floor, which costs a square root, is evaluated only for a touching pair.
template <class SpeedFloor>
inline double contact_time_before(const Vec3& dr, const Vec3& dv, double sigma, double horizon,
                                  SpeedFloor&& speed_floor) {
  const double b = dot(dr, dv);
  if (b >= 0.0) return kNever;  // moving apart (or tangent)
  const double c = norm2(dr) - sigma * sigma;
  if (c <= 0.0) return approaching(dr, dv, speed_floor()) ? 0.0 : kNever;  // touching: collide now unless grazing
  if (c > -2.0 * b * horizon * (1.0 + 1e-9)) return kNever;
  const double a = norm2(dv);
  const double discriminant = b * b - a * c;
  if (discriminant <= 0.0) return kNever;
  return c / (-b + std::sqrt(discriminant));
}

// The contact time with no horizon and a fixed speed floor.
inline double contact_time(const Vec3& dr, const Vec3& dv, double sigma, double speed_floor = 0.0) {
  return contact_time_before(dr, dv, sigma, kNever, [speed_floor] { return speed_floor; });
}

// First time t >= 0 at which gap(t) = gap + rate t + 0.5 accel t^2 reaches zero while closing
// (d gap/dt < 0 there). A gap already <= 0 and closing gives 0; kNever if it never closes.
// Used for walls and cell faces: gap is the signed distance to the plane in its normal direction.
inline double closing_time(double gap, double rate, double accel) {
  if (gap <= 0.0) {
    if (rate < 0.0 || (rate == 0.0 && accel < 0.0)) return 0.0;
    // Receding from a plane we are (by round-off) at or just beyond: the next closing is when the
    // parabola comes back, the root of 0.5 a t^2 + r t = 0 other than t = 0.
    gap = 0.0;
  }
  if (accel == 0.0) return rate < 0.0 ? gap / -rate : kNever;
  const double discriminant = rate * rate - 2.0 * accel * gap;
  if (discriminant < 0.0) return kNever;
  // Stable roots of A t^2 + B t + C (A = a/2, B = rate, C = gap): q = -(B + sign(B) sqrt(disc)) / 2.
  const double q = -0.5 * (rate + std::copysign(std::sqrt(discriminant), rate));
  if (q == 0.0) return kNever;  // rate = 0 and gap = 0 with accel > 0: moving away for good
  double best = kNever;
  for (double t : {q / (0.5 * accel), gap / q}) {
    if (!(t >= 0.0)) continue;
    const double slope = rate + accel * t;
    if (slope < 0.0) best = std::min(best, t);
  }
  return best;
}

// First time t in [0, horizon) at which |dr + dv t + da t^2 / 2| = sigma while closing, for
// relative motion with an acceleration (a particle rolling on a wall against a free one). The
// quartic f(t) = |.|^2 - sigma^2 is split at the roots of f'' and f' into monotonic pieces, and the
// first piece on which f falls through zero is bisected: no complex arithmetic, no missed root.
inline double contact_time_accelerated(const Vec3& dr, const Vec3& dv, const Vec3& da, double sigma, double horizon,
                                       double speed_floor = 0.0) {
  // f(t) = c4 t^4 + c3 t^3 + c2 t^2 + c1 t + c0
  const double c4 = 0.25 * norm2(da), c3 = dot(dv, da), c2 = norm2(dv) + dot(dr, da), c1 = 2.0 * dot(dr, dv);
  double c0 = norm2(dr) - sigma * sigma;
  auto f = [&](double t) { return (((c4 * t + c3) * t + c2) * t + c1) * t + c0; };
  auto f1 = [&](double t) { return ((4.0 * c4 * t + 3.0 * c3) * t + 2.0 * c2) * t + c1; };
  if (c0 <= 0.0) {
    if (approaching(dr, dv, speed_floor)) return 0.0;
    // Touching (or overlapping by round-off) but not approaching now: the relative acceleration may
    // bring them back together later, so look for that return as closing_time() does for planes.
    c0 = 0.0;
  }
  if (!(horizon > 0.0) || horizon == kNever) horizon = 1e300;
  // Roots of f'' = 12 c4 t^2 + 6 c3 t + 2 c2 in (0, horizon).
  std::vector<double> cuts{0.0};
  {
    const double a = 12.0 * c4, b = 6.0 * c3, c = 2.0 * c2;
    if (a != 0.0) {
      const double disc = b * b - 4.0 * a * c;
      if (disc >= 0.0) {
        const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        for (double r : {q / a, q != 0.0 ? c / q : kNever})
          if (r > 0.0 && r < horizon) cuts.push_back(r);
      }
    } else if (b != 0.0 && -c / b > 0.0 && -c / b < horizon) {
      cuts.push_back(-c / b);
    }
  }
  std::sort(cuts.begin(), cuts.end());
  cuts.push_back(horizon);
  // On each piece f' is monotonic: split further at its root.
  std::vector<double> points{0.0};
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    double lo = cuts[k], hi = cuts[k + 1];
    const double flo = f1(lo), fhi = f1(hi);
    if ((flo < 0.0) != (fhi < 0.0)) {
      for (int it = 0; it < 2100 && hi - lo > 1e-15 * (1.0 + hi); ++it) {
        const double mid = 0.5 * (lo + hi);
        ((f1(mid) < 0.0) == (flo < 0.0) ? lo : hi) = mid;
      }
      points.push_back(0.5 * (lo + hi));
    }
    points.push_back(cuts[k + 1]);
  }
  // First monotonic piece on which f drops through zero.
  for (std::size_t k = 0; k + 1 < points.size(); ++k) {
    double lo = points[k], hi = points[k + 1];
    if (f(lo) > 0.0 && f(hi) <= 0.0) {
      for (int it = 0; it < 2100 && hi - lo > 1e-15 * (1.0 + hi); ++it) {
        const double mid = 0.5 * (lo + hi);
        (f(mid) > 0.0 ? lo : hi) = mid;
      }
      return lo;  // the last time still apart: the collision finds them touching, not overlapping
    }
  }
  return kNever;
}

}  // namespace grainflow::edmd
