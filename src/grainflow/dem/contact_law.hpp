// What a contact law is: a small value type the engine's force loop runs as a template parameter
// (no virtual call per pair), which also carries its name, reads and checks its own case keys, turns
// them into parameters, and states its closed forms. The ContactLaw concept lists it all; the
// registry (contact_law_registry.hpp) names the laws a case may choose.
#pragma once

#include <concepts>
#include <cstddef>
#include <optional>
#include <ranges>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/config/contact_parameters.hpp"
#include "grainflow/dem/contact_kinematics.hpp"

namespace grainflow {
class TomlReader;
}

namespace grainflow::dem {

// The conditions of a head-on binary impact without gravity: the bodies' effective mass and radius
// (m_i m_j / (m_i + m_j) and R_i R_j / (R_i + R_j); a sphere's own against a wall) and their
// closing speed. A law with linear springs needs the mass only; a Hertzian one all three.
struct HeadOnImpact {
  double effective_mass = 0.0;    // kg
  double effective_radius = 0.0;  // m
  double speed = 0.0;             // m/s
};

// A head-on binary contact without gravity, from the law's closed form: how long it lasts and the
// ratio of separation to approach speed. A contact that never ends (overdamped) has an infinite
// duration and restitution 0.
struct BinaryContact {
  double duration = 0.0;     // s
  double restitution = 0.0;  // e
};

// One line of `grainflow check`'s contact part: a label and its formatted value.
struct CheckLine {
  std::string label, value;
};

// A parameter set the law cannot run, named by its key in [contact].
struct ParameterProblem {
  std::string key, reason;
};

template <class L>
concept ContactLaw = requires(const typename L::Params& params, typename L::State& state, const ContactKinematics& kin,
                              const HeadOnImpact& impact, double number, int count, TomlReader& table,
                              ContactParameters& read_into, const ContactParameters& wall, const ContactConfig& contact,
                              const SpeciesConfig& species, const std::vector<SpeciesConfig>& species_list) {
  // Identity and case keys.
  { L::name } -> std::convertible_to<std::string_view>;
  requires std::ranges::range<decltype(L::keys)>;                 // [contact] keys besides model and friction
  requires std::ranges::range<decltype(L::wall_keys)>;            // [walls.FACE] keys besides friction
  { L::stiffness_key } -> std::convertible_to<std::string_view>;  // the key of the normal stiffness
  { L::calibrated_by_stiffness } -> std::convertible_to<bool>;    // `grainflow calibrate` may vary it
  { L::read(table, read_into) } -> std::same_as<void>;
  { L::read_wall(table, read_into) } -> std::same_as<void>;
  // Parameters of a run: between particles (the reference species gives material defaults), and
  // against a wall given its own law keys and friction.
  { L::pair_params(contact, species) } -> std::same_as<typename L::Params>;
  { L::wall_params(params, wall, number) } -> std::same_as<typename L::Params>;
  { L::problem(params, impact) } -> std::same_as<std::optional<ParameterProblem>>;
  // What the law needs of the species (a key of [[species]], the reason naming the species), checked
  // before any parameters are made.
  { L::species_problem(species_list) } -> std::same_as<std::optional<ParameterProblem>>;
  // Closed forms of a head-on impact (for the time step: two of the lightest spheres).
  { L::binary_contact(params, impact) } -> std::same_as<BinaryContact>;
  { L::time_step(params, impact, count) } -> std::same_as<double>;      // resolves a contact in >= count steps
  { L::loading_stiffness(params, impact) } -> std::same_as<double>;     // N/m, giving its peak overlap v sqrt(m / k)
  { L::tangential_stiffness(params, impact) } -> std::same_as<double>;  // N/m, at that overlap
  { L::describe(params, impact) } -> std::same_as<std::vector<CheckLine>>;
  // The force on i (normal magnitude, tangential vector), advancing the pair's memory by dt.
  { L::force(params, state, kin, number) } -> std::same_as<ContactForce>;
  // J, the energy the contact's springs hold at this overlap (and effective radius) and memory (the
  // energy budget).
  { L::elastic_energy(params, std::as_const(state), number, number) } -> std::same_as<double>;
};

// A cohesive law (adhesion) also keeps a contact after first touch until the surfaces are pulled
// apart to detach_overlap (< 0: a neck), and bounds sliding by its own load (adhesion presses the
// surfaces together beyond the normal force). The engine keeps such contacts alive and lists pairs
// far enough apart for them; a law without adhesion has neither.
template <class L>
concept CohesiveContactLaw = ContactLaw<L> && requires(const typename L::Params& params, double number) {
  { L::detach_overlap(params, number) } -> std::same_as<double>;        // m, for effective radius `number`
  { L::sliding_load(params, number, number) } -> std::same_as<double>;  // N, for normal force, R*
};

// N: what the Coulomb limit multiplies, mu times this (|F_n| for a law without adhesion).
template <ContactLaw L>
double sliding_load(const typename L::Params& p, double normal_force, double effective_radius) {
  if constexpr (CohesiveContactLaw<L>) return L::sliding_load(p, normal_force, effective_radius);
  else return normal_force < 0.0 ? -normal_force : normal_force;
}

}  // namespace grainflow::dem
