// Walton–Braun contact law (Lan 1994, section 2.4): partially latching normal spring with
// loading stiffness K1, unloading/reloading stiffness K2 = K1/e^2, and the incremental
// Mindlin–Deresiewicz-like tangential force with stiffness scaling `scalek` and Coulomb limit.
//
// Reference model: every other contact law follows this shape (contact_law.hpp). The case keys
// and closed forms are in walton_braun.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "grainflow/dem/contact_law.hpp"

namespace grainflow::dem {

struct WaltonBraun {
  static constexpr std::string_view name = "walton_braun";
  static constexpr std::array<std::string_view, 3> keys = {"k1", "restitution", "ratk"};
  static constexpr std::array<std::string_view, 1> wall_keys = {"restitution"};
  static constexpr std::string_view stiffness_key = "k1";
  static constexpr bool calibrated_by_stiffness = true;  // Lan's calibration of K1 (section 4.1.3)

  struct Params {
    double k1 = 0.0;           // N/m, loading stiffness
    double k2 = 0.0;           // N/m, unloading stiffness, k1 / e^2 (eq. 2-4-12)
    double k0 = 0.0;           // N/m, initial tangential stiffness, ratk * k1 (eq. 2-4-20)
    double friction = 0.0;     // Coulomb coefficient mu
    double restitution = 1.0;  // e, kept exactly for the closed forms (k2 holds it rounded)
  };

  // Per-contact memory, kept while the pair overlaps and cleared on separation.
  struct State {
    Vec3 tangential_force;   // N, force on i at the previous step
    double t_star = 0.0;     // N, T* of eq. (2-4-21): signed force at the last slip reversal
    double alpha_max = 0.0;  // m, largest overlap on the current K1 line; alpha0 = alpha_max (1 - k1/k2)
    bool unloading = false;  // tangential mode since the last reversal
  };

  static Params make(double k1, double restitution, double ratk, double friction) {
    return {k1, k1 / (restitution * restitution), ratk * k1, friction, restitution};
  }

  // [contact]: k1 (required), restitution (default 0.9), ratk (default Mindlin's, below).
  static void read(TomlReader& table, ContactParameters& out);
  // [walls.FACE]: restitution (default the particles').
  static void read_wall(TomlReader& table, ContactParameters& out);
  // ratk defaults to Mindlin's 2 (1 - nu) / (2 - nu), nu of the reference species or 0.3.
  static Params pair_params(const ContactConfig& contact, const SpeciesConfig& reference);
  static Params wall_params(const Params& pair, const ContactParameters& wall, double friction);
  static std::optional<ParameterProblem> problem(const Params&, const HeadOnImpact&) { return std::nullopt; }
  static std::optional<ParameterProblem> species_problem(const std::vector<SpeciesConfig>&) { return std::nullopt; }

  // Loading quarter-period on K1 plus unloading on K2; e = sqrt(K1 / K2) exactly.
  static BinaryContact binary_contact(const Params& p, const HeadOnImpact& impact);
  // eq. (2-5-4): dt = (pi e / n) sqrt(m / (2 K1)), m the lightest sphere (twice the pair's m_eff).
  static double time_step(const Params& p, const HeadOnImpact& pair, int collision_steps);
  static double loading_stiffness(const Params& p, const HeadOnImpact&) { return p.k1; }
  static double tangential_stiffness(const Params& p, const HeadOnImpact&) { return p.k0; }
  static std::vector<CheckLine> describe(const Params& p, const HeadOnImpact& impact);

  // Residual overlap alpha0 at which the unloading line K2 reaches zero force.
  static double residual_overlap(const Params& p, const State& s) { return s.alpha_max * (1.0 - p.k1 / p.k2); }

  // What the springs give back: unloading on K2 from here to alpha0, 1/2 K2 (alpha - alpha0)^2 (the
  // rest of the loading work, 1 - e^2 of it, is lost), and the tangential force's F^2 / (2 K0), its
  // release at the initial stiffness K0 (after a reversal the stiffness starts at K0).
  static double elastic_energy(const Params& p, const State& s, double overlap, double /*effective_radius*/) {
    const double stretch = std::max(0.0, overlap - residual_overlap(p, s));
    const double tangential = p.k0 > 0.0 ? 0.5 * norm2(s.tangential_force) / p.k0 : 0.0;
    return 0.5 * p.k2 * stretch * stretch + tangential;
  }

  // Always inlined: the pair loop is mostly this function, and with the wall loops beside it the
  // compiler would otherwise call it (~10 % of a dense flow's step, measured).
  [[gnu::always_inline]] static ContactForce force(const Params& p, State& s, const ContactKinematics& c, double dt) {
    ContactForce out;
    // Normal: F = min(K1 alpha, K2 (alpha - alpha0)) (eq. 2-4-1), never attractive.
    const double alpha0 = residual_overlap(p, s);
    const double loading_force = p.k1 * c.overlap;
    const double unloading_force = p.k2 * (c.overlap - alpha0);
    if (loading_force <= unloading_force) {
      s.alpha_max = c.overlap;  // on the K1 line: the turning point moves with alpha
      out.normal = loading_force;
    } else {
      out.normal = std::max(0.0, unloading_force);
    }
    if (p.friction > 0.0) out.tangential = tangential(p, s, c, out.normal, dt);
    return out;
  }

 private:
  [[gnu::always_inline]] static Vec3 tangential(const Params& p, State& s, const ContactKinematics& c, double normal_force,
                                                double dt) {
    const double limit = p.friction * normal_force;  // mu N
    // Old force rotated into the current tangent plane (eq. 2-4-16).
    Vec3 old_force = s.tangential_force - dot(s.tangential_force, c.normal) * c.normal;
    const Vec3 slip = c.slip_velocity * dt;  // Delta S of i relative to j
    const double old_magnitude = norm(old_force);
    Vec3 direction;  // t of eq. (2-4-17): along the old force
    if (old_magnitude > 0.0) {
      direction = old_force * (1.0 / old_magnitude);
    } else {
      const double slip_magnitude = norm(slip);
      if (slip_magnitude == 0.0 || limit == 0.0) {
        s.tangential_force = Vec3{};
        return Vec3{};
      }
      direction = slip * (-1.0 / slip_magnitude);  // the force will grow opposite to the slip
    }
    const double along = dot(slip, direction);
    const Vec3 slip_along = along * direction;   // Delta S_t
    const Vec3 slip_across = slip - slip_along;  // Delta S_n (eq. 2-4-18)

    // The force along `direction` grows when the slip opposes it (loading), shrinks otherwise.
    const bool unloading = along > 0.0;
    const double magnitude = std::min(old_magnitude, limit);  // T
    if (unloading != s.unloading) {                           // slip reversed: T* takes the current T
      s.t_star = magnitude;
      s.unloading = unloading;
    }
    double scale = 0.0;  // scalek of eq. (2-4-21)
    if (!unloading) {
      const double denom = limit - s.t_star;
      if (denom > 0.0) scale = std::cbrt(std::max(0.0, 1.0 - (magnitude - s.t_star) / denom));
    } else {
      const double denom = limit + s.t_star;
      if (denom > 0.0) scale = std::cbrt(std::max(0.0, 1.0 - (s.t_star - magnitude) / denom));
    }
    Vec3 force = old_force - (p.k0 * scale) * slip_along - p.k0 * slip_across;  // eq. (2-4-13)

    if (old_magnitude > 0.0 && dot(force, direction) < 0.0) {
      // The force passed through zero: seen from its new direction the reversal point lies on the
      // other side, and unloading becomes loading.
      s.t_star = -s.t_star;
      s.unloading = !s.unloading;
    }
    const double new_magnitude = norm(force);
    if (new_magnitude > limit) force *= limit / new_magnitude;  // Coulomb sliding
    s.tangential_force = force;
    return force;
  }
};

}  // namespace grainflow::dem
