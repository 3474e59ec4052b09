// The Hertz–Mindlin law's case keys, parameters and closed forms.
#include "grainflow/dem/hertz_mindlin.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include <fmt/format.h>

#include "grainflow/config/toml_reader.hpp"
#include "grainflow/dem/dem_engine_impl.hpp"

namespace grainflow::dem {
namespace {

constexpr double kRigid = std::numeric_limits<double>::infinity();
constexpr double kDefaultRestitution = 0.9;
constexpr double kRayleighFraction = 0.2;  // dt <= 0.2 T_R (20-40 % is the usual advice; the low end)

// The scaled equation's step: its error falls as h^5/4 (the x^1/4 at first touch), 2e-7 in e and
// 1e-7 of the duration at this h.
constexpr double kScaledStep = 2e-4;

void read_material(TomlReader& r, ContactParameters& out) {
  if (r.has("youngs_modulus")) {
    const double e = r.number("youngs_modulus", 0.0);
    if (!(e > 0.0)) r.fail("youngs_modulus", "must be positive");
    out.set("youngs_modulus", e);
  }
  if (r.has("poisson_ratio")) {
    const double nu = r.number("poisson_ratio", 0.0);
    if (!(nu >= 0.0 && nu < 0.5)) r.fail("poisson_ratio", "must lie in [0, 0.5)");
    out.set("poisson_ratio", nu);
  }
}

double read_restitution(TomlReader& r, double fallback) {
  const double e = r.number("restitution", fallback);
  if (!(e > 0.0 && e <= 1.0)) r.fail("restitution", "must lie in (0, 1]");
  return e;
}

}  // namespace

HertzMindlin::ScaledImpact HertzMindlin::scaled_impact(double damping) {
  const double k = damping * std::sqrt(1.5);
  auto force = [k](double x, double v) { return x * std::sqrt(x) + k * std::sqrt(std::sqrt(x)) * v; };
  auto acceleration = [&](double x, double v) { return x > 0.0 ? -force(x, v) : 0.0; };
  const double h = kScaledStep;
  double x = 0.0, v = 1.0, t = 0.0;
  for (long step = 0; step < 100000000; ++step) {
    const double a1 = acceleration(x, v);
    const double x2 = x + 0.5 * h * v, v2 = v + 0.5 * h * a1, a2 = acceleration(x2, v2);
    const double x3 = x + 0.5 * h * v2, v3 = v + 0.5 * h * a2, a3 = acceleration(x3, v3);
    const double x4 = x + h * v3, v4 = v + h * a3, a4 = acceleration(x4, v4);
    const double xn = x + h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
    const double vn = v + h / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
    // The end, placed by linear interpolation: the overlap back at zero, or (receding) the force.
    if (xn <= 0.0) {
      const double f = x / (x - xn);
      return {-(v + f * (vn - v)), t + f * h};
    }
    if (vn < 0.0) {
      const double f0 = force(x, v), f1 = force(xn, vn);
      if (f1 <= 0.0) {
        const double f = f0 / (f0 - f1);
        return {-(v + f * (vn - v)), t + f * h};
      }
    }
    x = xn, v = vn, t += h;
  }
  return {0.0, kRigid};  // not reached for a finite damping
}

double HertzMindlin::damping_for(double restitution) {
  if (restitution >= 1.0) return 0.0;
  static std::mutex mutex;  // cases ask for a few values, many times (walls, checks, theory)
  static std::map<double, double> known;
  const std::lock_guard<std::mutex> lock(mutex);
  if (const auto it = known.find(restitution); it != known.end()) return it->second;
  // e(c) falls from 1 at c = 0 towards 0: bracket, then the Illinois variant of regula falsi on
  // e(c) - e, which converges superlinearly and keeps the bracket.
  double lo = 0.0, e_lo = 1.0 - restitution;
  double hi = 0.5, e_hi = scaled_impact(hi).restitution - restitution;
  while (e_hi > 0.0) {
    lo = hi, e_lo = e_hi;
    hi *= 2.0;
    e_hi = scaled_impact(hi).restitution - restitution;
  }
  int side = 0;
  double c = hi;
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-13 * hi; ++iteration) {
    c = (lo * e_hi - hi * e_lo) / (e_hi - e_lo);
    const double e_c = scaled_impact(c).restitution - restitution;
    if (e_c == 0.0) break;
    if ((e_c > 0.0) == (e_lo > 0.0)) {
      lo = c, e_lo = e_c;
      if (side == -1) e_hi *= 0.5;
      side = -1;
    } else {
      hi = c, e_hi = e_c;
      if (side == 1) e_lo *= 0.5;
      side = 1;
    }
    if (std::fabs(e_c) < 1e-12) break;
  }
  known.emplace(restitution, c);
  return c;
}

HertzMindlin::Params HertzMindlin::make(double youngs_modulus, double poisson_ratio, double restitution,
                                        double friction, double other_youngs_modulus, double other_poisson_ratio) {
  Params p;
  p.youngs_modulus = youngs_modulus;
  p.poisson_ratio = poisson_ratio;
  const double nu = poisson_ratio, nu_o = other_poisson_ratio;
  const double compliance_o = std::isinf(other_youngs_modulus) ? 0.0 : 1.0 / other_youngs_modulus;
  p.e_star = 1.0 / ((1.0 - nu * nu) / youngs_modulus + (1.0 - nu_o * nu_o) * compliance_o);
  p.g_star = 1.0 / (2.0 * (2.0 - nu) * (1.0 + nu) / youngs_modulus + 2.0 * (2.0 - nu_o) * (1.0 + nu_o) * compliance_o);
  p.restitution = restitution;
  p.damping = damping_for(restitution);
  p.scaled_duration = scaled_impact(p.damping).duration;
  p.friction = friction;
  return p;
}

void HertzMindlin::read(TomlReader& r, ContactParameters& out) {
  out.set("restitution", read_restitution(r, kDefaultRestitution));
}

void HertzMindlin::read_wall(TomlReader& r, ContactParameters& out) {
  if (r.has("restitution")) out.set("restitution", read_restitution(r, kDefaultRestitution));
  read_material(r, out);
}

HertzMindlin::Params HertzMindlin::pair_params(const ContactConfig& contact, const SpeciesConfig& reference) {
  // The case checks have made sure every species has a Young's modulus (and one material).
  const double e = reference.youngs_modulus, nu = reference.poisson_ratio >= 0.0 ? reference.poisson_ratio : 0.3;
  return make(e, nu, contact.parameters.at("restitution"), contact.friction, e, nu);
}

HertzMindlin::Params HertzMindlin::wall_params(const Params& pair, const ContactParameters& wall, double friction) {
  const double wall_modulus = wall.get("youngs_modulus", kRigid);
  const double wall_poisson = wall.get("poisson_ratio", wall.has("youngs_modulus") ? 0.3 : 0.0);
  return make(pair.youngs_modulus, pair.poisson_ratio, wall.get("restitution", pair.restitution), friction,
              wall_modulus, wall_poisson);
}

std::optional<ParameterProblem> HertzMindlin::material_problem(const std::vector<SpeciesConfig>& species,
                                                               std::string_view law) {
  for (const SpeciesConfig& s : species) {
    if (!(s.youngs_modulus > 0.0))
      return ParameterProblem{"youngs_modulus", fmt::format("species '{}' has none: contact.model = \"{}\" needs each "
                                                            "species' Young's modulus (Pa) and poisson_ratio",
                                                            s.name, law)};
    if (s.youngs_modulus != species.front().youngs_modulus || s.poisson_ratio != species.front().poisson_ratio)
      return ParameterProblem{"youngs_modulus",
                              fmt::format("species '{}' and '{}' are of different materials; {} takes one material for "
                                          "every species (give each the same youngs_modulus and poisson_ratio)",
                                          s.name, species.front().name, law)};
  }
  return std::nullopt;
}

double HertzMindlin::peak_overlap(const Params& p, const HeadOnImpact& impact) {
  // Elastic Hertz (damping only lowers it): (15 m* v^2 / (16 E* sqrt(R*)))^2/5.
  return std::pow(15.0 * impact.effective_mass * impact.speed * impact.speed /
                      (16.0 * p.e_star * std::sqrt(impact.effective_radius)),
                  0.4);
}

BinaryContact HertzMindlin::binary_contact(const Params& p, const HeadOnImpact& impact) {
  if (!(impact.speed > 0.0)) return {kRigid, p.restitution};  // an impact at no speed never ends
  const double k = 4.0 / 3.0 * p.e_star * std::sqrt(impact.effective_radius);
  const double length = std::pow(impact.effective_mass * impact.speed * impact.speed / k, 0.4);
  return {p.scaled_duration * length / impact.speed, p.restitution};
}

double HertzMindlin::rayleigh_time(const Params& p, const HeadOnImpact& pair) {
  // The pair is two equal spheres: each of radius 2 R* and mass 2 m*.
  const double radius = 2.0 * pair.effective_radius, mass = 2.0 * pair.effective_mass;
  const double density = mass / (4.0 / 3.0 * M_PI * radius * radius * radius);
  const double shear_modulus = p.youngs_modulus / (2.0 * (1.0 + p.poisson_ratio));
  return M_PI * radius * std::sqrt(density / shear_modulus) / (0.1631 * p.poisson_ratio + 0.8766);
}

double HertzMindlin::time_step(const Params& p, const HeadOnImpact& pair, int collision_steps) {
  return std::min(binary_contact(p, pair).duration / collision_steps, kRayleighFraction * rayleigh_time(p, pair));
}

double HertzMindlin::loading_stiffness(const Params& p, const HeadOnImpact& impact) {
  const double overlap = peak_overlap(p, impact);
  return overlap > 0.0 ? impact.effective_mass * std::pow(impact.speed / overlap, 2) : kRigid;
}

double HertzMindlin::tangential_stiffness(const Params& p, const HeadOnImpact& impact) {
  return 8.0 * p.g_star * std::sqrt(impact.effective_radius * peak_overlap(p, impact));
}

std::vector<CheckLine> HertzMindlin::describe(const Params& p, const HeadOnImpact& impact) {
  const BinaryContact b = binary_contact(p, impact);
  return {{"E, nu (particles)", fmt::format("{:.6g} Pa, {:.3g}", p.youngs_modulus, p.poisson_ratio)},
          {"E*, G* (pair)", fmt::format("{:.6g} Pa, {:.6g} Pa", p.e_star, p.g_star)},
          {"e (any impact speed)", fmt::format("{:.6g}  (damping constant {:.6g})", p.restitution, p.damping)},
          {"Hertz duration", fmt::format("{:.6g} s at {:.6g} m/s  (peak overlap {:.4g} m)", b.duration, impact.speed,
                                         peak_overlap(p, impact))},
          {"Rayleigh time",
           fmt::format("{:.6g} s  (time step bound {:.3g} of it)", rayleigh_time(p, impact), kRayleighFraction)}};
}

// The engine's time loop for this law, without and with rolling resistance, compiled here once
// (dem_engine_impl.hpp).
template class DemEngine<HertzMindlin, false>;
template class DemEngine<HertzMindlin, true>;

}  // namespace grainflow::dem
