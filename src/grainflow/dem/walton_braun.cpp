// The Walton–Braun law's case keys, parameters and closed forms (Lan 1994 sections 2.4-2.5).
#include "grainflow/dem/walton_braun.hpp"

#include <cmath>

#include <fmt/format.h>

#include "grainflow/config/toml_reader.hpp"
#include "grainflow/dem/dem_engine_impl.hpp"

namespace grainflow::dem {

void WaltonBraun::read(TomlReader& r, ContactParameters& out) {
  const double k1 = r.required_number("k1");
  if (!(k1 > 0.0)) r.fail("k1", "must be positive");
  out.set("k1", k1);
  const double restitution = r.number("restitution", 0.9);
  if (!(restitution > 0.0 && restitution <= 1.0)) r.fail("restitution", "must lie in (0, 1]");
  out.set("restitution", restitution);
  if (r.has("ratk")) {
    const double ratk = r.number("ratk", 0.0);
    if (!(ratk > 0.0)) r.fail("ratk", "must be positive");
    out.set("ratk", ratk);
  }
}

void WaltonBraun::read_wall(TomlReader& r, ContactParameters& out) {
  if (!r.has("restitution")) return;
  // A soft-sphere wall needs a finite K2 = K1 / e^2: e = 0 is refused.
  const double restitution = r.number("restitution", 0.0);
  if (!(restitution > 0.0 && restitution <= 1.0)) r.fail("restitution", "must lie in (0, 1]");
  out.set("restitution", restitution);
}

WaltonBraun::Params WaltonBraun::pair_params(const ContactConfig& contact, const SpeciesConfig& reference) {
  double ratk = contact.parameters.get("ratk", -1.0);
  if (ratk <= 0.0) {
    const double nu = reference.poisson_ratio >= 0.0 ? reference.poisson_ratio : 0.3;
    ratk = 2.0 * (1.0 - nu) / (2.0 - nu);
  }
  return make(contact.parameters.at("k1"), contact.parameters.at("restitution"), ratk, contact.friction);
}

WaltonBraun::Params WaltonBraun::wall_params(const Params& pair, const ContactParameters& wall, double friction) {
  Params p = pair;
  p.restitution = wall.get("restitution", pair.restitution);
  p.k2 = p.k1 / (p.restitution * p.restitution);
  p.friction = friction;
  return p;
}

BinaryContact WaltonBraun::binary_contact(const Params& p, const HeadOnImpact& impact) {
  const double m = impact.effective_mass;
  return {0.5 * M_PI * (std::sqrt(m / p.k1) + std::sqrt(m / p.k2)), p.restitution};
}

double WaltonBraun::time_step(const Params& p, const HeadOnImpact& pair, int collision_steps) {
  const double mass = 2.0 * pair.effective_mass;  // exact: the lightest sphere's
  return M_PI * p.restitution / collision_steps * std::sqrt(mass / (2.0 * p.k1));
}

std::vector<CheckLine> WaltonBraun::describe(const Params& p, const HeadOnImpact&) {
  return {{"K1 (loading)", fmt::format("{:.6g} N/m", p.k1)},
          {"K2 = K1/e^2 (unloading)", fmt::format("{:.6g} N/m", p.k2)},
          {"e = sqrt(K1/K2)", fmt::format("{:.6g}", p.restitution)},
          {"K0 = ratk K1 (tangential)", fmt::format("{:.6g} N/m", p.k0)}};
}

// The engine's time loop for this law, without and with rolling resistance, compiled here once
// (dem_engine_impl.hpp).
template class DemEngine<WaltonBraun, false>;
template class DemEngine<WaltonBraun, true>;

}  // namespace grainflow::dem
