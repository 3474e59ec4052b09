// JKR adhesion (Johnson, Kendall & Roberts 1971) for fine or moist powders: Hertz–Mindlin's
// material law (E*, G*, Tsuji damping, Mindlin tangential spring) with the contact radius a and the
// normal force of an adhesive elastic contact of surface energy Gamma (work of adhesion w = 2 Gamma
// between two surfaces of one material):
//
//   delta = a^2 / R* - sqrt(2 pi w a / E*),   F = 4 E* a^3 / (3 R*) - sqrt(8 pi w E* a^3)
//
// so that, as Thornton (and Johnson) state it, the force pulling the surfaces apart peaks at the
// pull-off force F_c = 3 pi Gamma R* (= 3/2 pi w R*, at a^3 = 9 pi w R*^2 / (8 E*)). Touching
// surfaces snap into contact at delta = 0 with a = (2 pi w R*^2 / E*)^1/3 and F = -8/9 F_c; pulled
// apart, the contact holds on a neck down to delta_c = -(3/4) (pi^2 w^2 R* / E*^2)^1/3 (F = -5/9 F_c)
// and then breaks. Approach and separation follow different paths (hysteresis): the energy of the
// two jumps is lost, so slow impacts stick. Sliding is bounded by mu (F + 2 F_c) (Thornton & Yin
// 1991): adhesion presses the surfaces together. The case keys and closed forms are in jkr.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "grainflow/dem/contact_law.hpp"
#include "grainflow/dem/hertz_mindlin.hpp"

namespace grainflow::dem {

struct Jkr {
  static constexpr std::string_view name = "jkr";
  static constexpr std::array<std::string_view, 2> keys = {"restitution", "surface_energy"};
  static constexpr std::array<std::string_view, 4> wall_keys = {"restitution", "youngs_modulus", "poisson_ratio",
                                                                "surface_energy"};
  static constexpr std::string_view stiffness_key = "youngs_modulus";
  static constexpr bool calibrated_by_stiffness = false;  // the stiffness is the material's

  struct Params {
    HertzMindlin::Params material;  // E*, G*, the damping constant (for restitution without adhesion)
    double surface_energy = 0.0;    // J/m^2, Gamma; w = 2 Gamma
  };

  struct State {
    Vec3 tangential_force;        // N, the tangential spring's force on i at the previous step
    double contact_radius = 0.0;  // m, a at the previous step (unloading scales the spring; Newton starts there)
  };

  // m: the contact radius a on the stable branch for overlap `overlap` (>= delta_c): the largest root
  // of t^4 - R* c t - R* delta = 0, t = sqrt(a), c = sqrt(2 pi w / E*), by Newton's method from
  // above (the quartic is convex, so the iterates fall monotonically onto the root).
  // `guess` (m, e.g. the contact's radius a step ago; 0: none) only speeds it up: a Newton step
  // from any point where the quartic rises lands above the root, whence the iterates fall onto it.
  static double contact_radius(double e_star, double work_of_adhesion, double effective_radius, double overlap,
                               double guess = 0.0) {
    const double c = std::sqrt(2.0 * M_PI * work_of_adhesion / e_star);
    const double r = effective_radius;
    if (c == 0.0) return overlap > 0.0 ? std::sqrt(r * overlap) : 0.0;  // Hertz
    const double rc = r * c;
    double t = 0.0;
    const double t_guess = std::sqrt(guess);
    const double slope_guess = 4.0 * t_guess * t_guess * t_guess - rc;
    if (slope_guess > 0.0) {  // on the rising side of the quartic (beyond t_min)
      const double g = t_guess * t_guess * t_guess * t_guess - rc * t_guess - r * overlap;
      t = g >= 0.0 ? t_guess : t_guess - g / slope_guess;
    }
    if (!(t > 0.0) ||
        t > 2.0 * t_guess) {  // no guess, or far off: g(t) >= 0 where t^4 / 2 covers R* c t and R* |delta|
      t = std::max(std::cbrt(2.0 * rc), std::sqrt(std::sqrt(2.0 * r * std::fabs(overlap))));
    }
    for (int iteration = 0; iteration < 60; ++iteration) {
      const double t2 = t * t;
      const double g = t2 * t2 - rc * t - r * overlap;
      const double slope = 4.0 * t2 * t - rc;
      double next = t - g / slope;
      // Not below t_min, where g' = 0: below delta_c there is no root and the curve ends there.
      if (!(4.0 * next * next * next - rc > 0.0)) next = std::cbrt(0.25 * rc);
      if (!(next < t) || t - next <= 1e-15 * t) {
        t = next;
        break;
      }
      t = next;
    }
    return t * t;
  }

  // N, the adhesive elastic force at contact radius a: 4 E* a^3 / (3 R*) - sqrt(8 pi w E* a^3).
  static double elastic_force(const Params& p, double a, double effective_radius) {
    const double e = p.material.e_star, w = 2.0 * p.surface_energy;
    return 4.0 * e * a * a * a / (3.0 * effective_radius) - std::sqrt(8.0 * M_PI * w * e * a * a * a);
  }

  // Always inlined: the pair loop is mostly this function, and with the wall loops beside it the
  // compiler would otherwise call it (~10 % of a dense flow's step, measured).
  [[gnu::always_inline]] static ContactForce force(const Params& p, State& s, const ContactKinematics& c, double dt) {
    const HertzMindlin::Params& m = p.material;
    ContactForce out;
    const double a = contact_radius(m.e_star, 2.0 * p.surface_energy, c.effective_radius, c.overlap, s.contact_radius);
    const double normal_stiffness = 2.0 * m.e_star * a;  // S_n, Tsuji's damping as in Hertz–Mindlin
    const double damping = m.damping * std::sqrt(normal_stiffness * c.effective_mass);
    out.normal = elastic_force(p, a, c.effective_radius) - damping * c.normal_velocity;
    const double previous = s.contact_radius;
    s.contact_radius = a;
    if (m.friction <= 0.0) return out;
    // Mindlin on the JKR patch, the stored force scaled down with a while it shrinks.
    out.tangential = HertzMindlin::mindlin_tangential(m, s.tangential_force, a, a < previous ? a / previous : 1.0, c,
                                                      dt, m.friction * sliding_load(p, out.normal, c.effective_radius));
    return out;
  }

  // N, F_c = 3 pi Gamma R*.
  static double pull_off_force(const Params& p, double effective_radius) {
    return 3.0 * M_PI * p.surface_energy * effective_radius;
  }
  // m, delta_c = -(3/4) (pi^2 w^2 R* / E*^2)^1/3.
  static double detach_overlap(const Params& p, double effective_radius) {
    const double w = 2.0 * p.surface_energy, e = p.material.e_star;
    return -0.75 * std::cbrt(M_PI * M_PI * w * w * effective_radius / (e * e));
  }
  // N, mu times this bounds sliding: F + 2 F_c (never below zero).
  static double sliding_load(const Params& p, double normal_force, double effective_radius) {
    return std::max(0.0, normal_force + 2.0 * pull_off_force(p, effective_radius));
  }

  // J, U(a) = integral of F d(delta) from the separated state: 8 E* a^5 / (15 R*^2)
  // - (4/3) sqrt(2 pi w E*) a^7/2 / R* + pi w a^2. The jumps of U at snap-on and at break are the
  // energy JKR's hysteresis loses.
  static double adhesive_energy(const Params& p, double a, double effective_radius) {
    const double e = p.material.e_star, w = 2.0 * p.surface_energy, r = effective_radius;
    return 8.0 * e * std::pow(a, 5) / (15.0 * r * r) -
           (4.0 / 3.0) * std::sqrt(2.0 * M_PI * w * e) * std::pow(a, 3.5) / r + M_PI * w * a * a;
  }
  // U(a) with the tangential spring's F^2 / (2 S_t).
  static double elastic_energy(const Params& p, const State& s, double overlap, double effective_radius) {
    const double a = contact_radius(p.material.e_star, 2.0 * p.surface_energy, effective_radius, overlap);
    return adhesive_energy(p, a, effective_radius) + HertzMindlin::mindlin_energy(p.material, s.tangential_force, a);
  }

  // [contact]: restitution (0.9, of the same impact without adhesion), surface_energy (required).
  static void read(TomlReader& table, ContactParameters& out);
  // [walls.FACE]: restitution, youngs_modulus, poisson_ratio (as hertz_mindlin), surface_energy (the
  // particles' by default; 0 makes the wall non-adhesive).
  static void read_wall(TomlReader& table, ContactParameters& out);
  static Params pair_params(const ContactConfig& contact, const SpeciesConfig& reference);
  static Params wall_params(const Params& pair, const ContactParameters& wall, double friction);
  static std::optional<ParameterProblem> problem(const Params&, const HeadOnImpact&) { return std::nullopt; }
  static std::optional<ParameterProblem> species_problem(const std::vector<SpeciesConfig>& species);

  // A head-on impact integrated with this force (the duration until the neck breaks, the rebound
  // speed's ratio; e = 0 and an infinite duration when the spheres stick), cached.
  static BinaryContact binary_contact(const Params& p, const HeadOnImpact& impact);
  static BinaryContact integrate_impact(const Params& p, const HeadOnImpact& impact);
  // Hertz–Mindlin's bound (the contact's duration / collision_steps, a fifth of the Rayleigh time),
  // and half a period of a bonded pair's oscillations / collision_steps: strong adhesion holds
  // contacts at a0, a wider contact, and so a stiffer one, than a gentle impact's.
  static double time_step(const Params& p, const HeadOnImpact& pair, int collision_steps);
  // The radius where the adhesive force vanishes, a0^3 = 9 pi w R*^2 / (2 E*) (overlap a0^2 / (3 R*)).
  static double equilibrium_radius(const Params& p, double effective_radius);
  // N/m, dF/d delta of the JKR curve at a (its stable branch).
  static double normal_stiffness(const Params& p, double a, double effective_radius);
  // s, half the period of a bonded pair's small oscillations about a0, the smaller of the normal
  // one (m* on dF/d delta) and the tangential one (Mindlin's 8 G* a0 on m* / (1 + m* R*^2 / I*),
  // 2/7 m* for equal solid spheres, as sliding and rolling couple).
  static double bonded_half_period(const Params& p, const HeadOnImpact& pair);
  static double loading_stiffness(const Params& p, const HeadOnImpact& impact) {
    return HertzMindlin::loading_stiffness(p.material, impact);
  }
  static double tangential_stiffness(const Params& p, const HeadOnImpact& impact) {
    return HertzMindlin::tangential_stiffness(p.material, impact);
  }
  // m/s, the impact speed below which two elastic spheres stick: 1/2 m* v^2 = the energy of the
  // two jumps, sqrt(2 W / m*) with W = 0.5355 F_c^5/3 / (E*^2/3 R*^1/3).
  static double sticking_speed(const Params& p, const HeadOnImpact& impact);
  static std::vector<CheckLine> describe(const Params& p, const HeadOnImpact& impact);
};

}  // namespace grainflow::dem
