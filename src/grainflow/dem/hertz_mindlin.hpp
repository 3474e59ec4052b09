// Hertz–Mindlin contact law, as LIGGGHTS, EDEM and MercuryDPM users calibrate it: the Hertz normal
// force 4/3 E* sqrt(R*) delta^3/2 from the species' youngs_modulus and poisson_ratio, the Mindlin
// no-slip tangential stiffness 8 G* sqrt(R* delta) with its history and the Coulomb limit, and a
// viscous damping of Tsuji's form, c sqrt(m* S) (S the current stiffness), which makes the
// restitution coefficient independent of the impact speed. Its constant is found for the case's
// contact.restitution exactly, for a normal force that never pulls (no attraction), instead of the
// linear-oscillator estimate -2 sqrt(5/6) ln e / sqrt(ln^2 e + pi^2) of LIGGGHTS and EDEM, which
// gives a different e (Thornton et al. 2013). The case keys and closed forms are in hertz_mindlin.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

#include "grainflow/dem/contact_law.hpp"

namespace grainflow::dem {

struct HertzMindlin {
  static constexpr std::string_view name = "hertz_mindlin";
  static constexpr std::array<std::string_view, 1> keys = {"restitution"};
  static constexpr std::array<std::string_view, 3> wall_keys = {"restitution", "youngs_modulus", "poisson_ratio"};
  static constexpr std::string_view stiffness_key = "youngs_modulus";
  static constexpr bool calibrated_by_stiffness = false;  // the stiffness is the material's

  struct Params {
    double youngs_modulus = 0.0;  // Pa, the particles' material (a wall of its own combines with it)
    double poisson_ratio = 0.0;
    double e_star = 0.0;           // Pa, 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j
    double g_star = 0.0;           // Pa, 1/G* = 2 (2 - nu_i)(1 + nu_i)/E_i + 2 (2 - nu_j)(1 + nu_j)/E_j
    double restitution = 1.0;      // e, the binary normal restitution asked for
    double damping = 0.0;          // c of F_damp = -c sqrt(m* S) v, the same for the normal and tangential parts
    double scaled_duration = 0.0;  // the force's duration in units of (m* v^2 / k)^2/5 / v, k = 4/3 E* sqrt(R*)
    double friction = 0.0;         // Coulomb coefficient mu
  };

  struct State {
    Vec3 tangential_force;  // N, the tangential spring's force on i at the previous step
    double overlap = 0.0;   // m, the overlap at the previous step (unloading scales the spring)
  };

  // Params of a contact between the particles' material (E, nu) and a body of (E_other, nu_other);
  // E_other = infinity is a rigid body.
  static Params make(double youngs_modulus, double poisson_ratio, double restitution, double friction,
                     double other_youngs_modulus, double other_poisson_ratio);
  // A head-on impact in units of the overlap L = (m* v^2 / k)^2/5 and the time L / v, k = 4/3 E*
  // sqrt(R*): x'' = -x^3/2 - c sqrt(3/2) x^1/4 x', x(0) = 0, x'(0) = 1, ending when the force does.
  // It depends on the damping constant c only: so do e and the scaled duration.
  struct ScaledImpact {
    double restitution = 1.0, duration = 0.0;
  };
  static ScaledImpact scaled_impact(double damping);
  // The c whose scaled impact rebounds with `restitution` (to 1e-12).
  static double damping_for(double restitution);

  // Always inlined: the pair loop is mostly this function, and with the wall loops beside it the
  // compiler would otherwise call it (~10 % of a dense flow's step, measured).
  [[gnu::always_inline]] static ContactForce force(const Params& p, State& s, const ContactKinematics& c, double dt) {
    ContactForce out;
    const double contact_radius = std::sqrt(c.effective_radius * c.overlap);  // a = sqrt(R* delta)
    const double normal_stiffness = 2.0 * p.e_star * contact_radius;          // S_n = dF/d delta
    const double elastic = (2.0 / 3.0) * normal_stiffness * c.overlap;        // 4/3 E* sqrt(R*) delta^3/2
    const double damping = p.damping * std::sqrt(normal_stiffness * c.effective_mass);
    out.normal = std::max(0.0, elastic - damping * c.normal_velocity);  // never attractive
    if (p.friction <= 0.0) return out;
    // The patch's radius shrinks as sqrt(delta) while the contact unloads.
    const double unloading = c.overlap < s.overlap ? std::sqrt(c.overlap / s.overlap) : 1.0;
    s.overlap = c.overlap;
    out.tangential =
        mindlin_tangential(p, s.tangential_force, contact_radius, unloading, c, dt, p.friction * out.normal);
    return out;
  }

  // Mindlin's tangential spring-dashpot on a patch of radius a: S_t = 8 G* a. The spring's force
  // a step ago, `stored`, turned into the current tangent plane, shrinks by `unloading` (<= 1, the
  // patch's radius ratio) while the contact unloads (Mindlin–Deresiewicz: the annulus of the
  // shrinking patch releases its share), so that no energy is created; the new slip adds S_t dS.
  // Spring and dashpot together are capped at `limit` (Coulomb). Returns the tangential force on i;
  // `stored` becomes the spring's part of it.
  [[gnu::always_inline]] static Vec3 mindlin_tangential(const Params& p, Vec3& stored, double a, double unloading, const ContactKinematics& c,
                                 double dt, double limit) {
    const double tangential_stiffness = 8.0 * p.g_star * a;
    Vec3 spring = stored - dot(stored, c.normal) * c.normal;
    spring *= unloading;
    spring -= (tangential_stiffness * dt) * c.slip_velocity;
    const Vec3 viscous = (-p.damping * std::sqrt(tangential_stiffness * c.effective_mass)) * c.slip_velocity;
    Vec3 total = spring + viscous;
    const double magnitude = norm(total);
    if (magnitude > limit) {
      // Sliding: spring and dashpot together sit on the Coulomb limit.
      total *= magnitude > 0.0 ? limit / magnitude : 0.0;
      spring = total - viscous;
    }
    stored = spring;
    return total;
  }
  // J, the Mindlin spring's F^2 / (2 S_t) on a patch of radius a.
  static double mindlin_energy(const Params& p, const Vec3& stored, double a) {
    const double tangential_stiffness = 8.0 * p.g_star * a;
    return tangential_stiffness > 0.0 ? 0.5 * norm2(stored) / tangential_stiffness : 0.0;
  }

  // The Hertz spring's 8/15 E* sqrt(R*) delta^5/2 and the tangential spring's F^2 / (2 S_t).
  static double elastic_energy(const Params& p, const State& s, double overlap, double effective_radius) {
    const double contact_radius = std::sqrt(effective_radius * overlap);
    return (8.0 / 15.0) * p.e_star * contact_radius * overlap * overlap +
           mindlin_energy(p, s.tangential_force, contact_radius);
  }

  // [contact]: restitution (default 0.9); E and nu are the species' youngs_modulus and poisson_ratio.
  static void read(TomlReader& table, ContactParameters& out);
  // [walls.FACE]: restitution (default the particles'); youngs_modulus and poisson_ratio (rigid
  // when absent).
  static void read_wall(TomlReader& table, ContactParameters& out);
  static Params pair_params(const ContactConfig& contact, const SpeciesConfig& reference);
  static Params wall_params(const Params& pair, const ContactParameters& wall, double friction);
  static std::optional<ParameterProblem> problem(const Params&, const HeadOnImpact&) { return std::nullopt; }
  // Every species needs youngs_modulus, and all the same material (one E*, G* for every pair).
  static std::optional<ParameterProblem> species_problem(const std::vector<SpeciesConfig>& species) {
    return material_problem(species, name);
  }
  // The same, for any law of this material model called `law` (in the message).
  static std::optional<ParameterProblem> material_problem(const std::vector<SpeciesConfig>& species,
                                                          std::string_view law);

  // The damped Hertz impact at the impact's speed: e as asked, duration from the scaled equation.
  static BinaryContact binary_contact(const Params& p, const HeadOnImpact& impact);
  // The smaller of the Hertz contact's duration / collision_steps and a fifth of the Rayleigh time
  // pi R sqrt(rho / G) / (0.1631 nu + 0.8766) of the pair's spheres (the bound of LIGGGHTS and EDEM
  // users, which also holds for the waves of a dense packing whatever the impact speeds).
  static double time_step(const Params& p, const HeadOnImpact& pair, int collision_steps);
  static double rayleigh_time(const Params& p, const HeadOnImpact& pair);
  // The linear spring with the Hertz impact's peak overlap, m* (v / delta_max)^2, and S_t there.
  static double loading_stiffness(const Params& p, const HeadOnImpact& impact);
  static double tangential_stiffness(const Params& p, const HeadOnImpact& impact);
  static double peak_overlap(const Params& p, const HeadOnImpact& impact);
  static std::vector<CheckLine> describe(const Params& p, const HeadOnImpact& impact);
};

}  // namespace grainflow::dem
