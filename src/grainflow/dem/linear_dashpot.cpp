// The linear spring–dashpot's case keys, parameters and closed forms.
#include "grainflow/dem/linear_dashpot.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "grainflow/config/toml_reader.hpp"
#include "grainflow/dem/dem_engine_impl.hpp"

namespace grainflow::dem {

void LinearDashpot::read(TomlReader& r, ContactParameters& out) {
  const double kn = r.required_number("kn");
  if (!(kn > 0.0)) r.fail("kn", "must be positive");
  out.set("kn", kn);
  const double kt = r.number("kt", 2.0 / 7.0 * kn);
  if (kt < 0.0) r.fail("kt", "must not be negative");
  out.set("kt", kt);
  const double gamma_n = r.number("gamma_n", 0.0);
  if (gamma_n < 0.0) r.fail("gamma_n", "must not be negative");
  out.set("gamma_n", gamma_n);
  const double gamma_t = r.number("gamma_t", 0.5 * gamma_n);
  if (gamma_t < 0.0) r.fail("gamma_t", "must not be negative");
  out.set("gamma_t", gamma_t);
}

void LinearDashpot::read_wall(TomlReader& r, ContactParameters& out) {
  if (!r.has("gamma_n")) return;
  const double gamma_n = r.number("gamma_n", 0.0);
  if (gamma_n < 0.0) r.fail("gamma_n", "must not be negative");
  out.set("gamma_n", gamma_n);
}

LinearDashpot::Params LinearDashpot::pair_params(const ContactConfig& contact, const SpeciesConfig&) {
  const ContactParameters& k = contact.parameters;
  return {k.at("kn"), k.at("kt"), k.at("gamma_n"), k.at("gamma_t"), contact.friction};
}

LinearDashpot::Params LinearDashpot::wall_params(const Params& pair, const ContactParameters& wall, double friction) {
  Params p = pair;
  p.gamma_n = wall.get("gamma_n", pair.gamma_n);
  p.friction = friction;
  return p;
}

std::optional<ParameterProblem> LinearDashpot::problem(const Params& p, const HeadOnImpact& impact) {
  if (std::isfinite(binary_contact(p, impact).duration)) return std::nullopt;
  return ParameterProblem{"gamma_n",
                          "the contact is overdamped (gamma_n >= 2 sqrt(kn / m_eff)): spheres would never separate"};
}

BinaryContact LinearDashpot::binary_contact(const Params& p, const HeadOnImpact& impact) {
  const double omega0_sq = p.kn / impact.effective_mass;
  const double omega_sq = omega0_sq - 0.25 * p.gamma_n * p.gamma_n;
  if (!(omega_sq > 0.0)) return {std::numeric_limits<double>::infinity(), 0.0};
  const double duration = M_PI / std::sqrt(omega_sq);
  return {duration, std::exp(-0.5 * p.gamma_n * duration)};
}

double LinearDashpot::time_step(const Params& p, const HeadOnImpact& pair, int collision_steps) {
  return binary_contact(p, pair).duration / collision_steps;
}

std::vector<CheckLine> LinearDashpot::describe(const Params& p, const HeadOnImpact& impact) {
  return {{"kn, kt", fmt::format("{:.6g}, {:.6g} N/m", p.kn, p.kt)},
          {"gamma_n, gamma_t", fmt::format("{:.6g}, {:.6g} 1/s", p.gamma_n, p.gamma_t)},
          {"e (binary, closed form)", fmt::format("{:.6g}", binary_contact(p, impact).restitution)}};
}

// The engine's time loop for this law, without and with rolling resistance, compiled here once
// (dem_engine_impl.hpp).
template class DemEngine<LinearDashpot, false>;
template class DemEngine<LinearDashpot, true>;

}  // namespace grainflow::dem
