// The JKR law's case keys, parameters and closed forms.
#include "grainflow/dem/jkr.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>

#include <fmt/format.h>

#include "grainflow/config/toml_reader.hpp"
#include "grainflow/dem/dem_engine_impl.hpp"

namespace grainflow::dem {
namespace {

constexpr double kNever = std::numeric_limits<double>::infinity();
// Steps of the head-on impact's integration per Hertz duration: the ends (snap-on, the neck's
// break) are placed to dt / 2, 2.5e-5 of the duration.
constexpr int kImpactSteps = 20000;
// Spheres still together after this many Hertz durations count as stuck: a rebound against
// adhesion takes a few; a heavily damped pair creeps back into the adhesive well for far longer.
constexpr int kStuckDurations = 10;

// m: the contact radius at the neck's break, delta_c, where the curve turns: a^3 = pi w R*^2 / (8 E*).
double neck_radius(const Jkr::Params& p, double r) {
  return std::cbrt(M_PI * 2.0 * p.surface_energy * r * r / (8.0 * p.material.e_star));
}

double read_surface_energy(TomlReader& r) {
  const double gamma = r.number("surface_energy", 0.0);
  if (!(gamma >= 0.0)) r.fail("surface_energy", "must not be negative");
  return gamma;
}

}  // namespace

void Jkr::read(TomlReader& r, ContactParameters& out) {
  HertzMindlin::read(r, out);
  if (!r.has("surface_energy")) r.fail("surface_energy", "is required by contact.model = \"jkr\" (J/m^2)");
  out.set("surface_energy", read_surface_energy(r));
}

void Jkr::read_wall(TomlReader& r, ContactParameters& out) {
  HertzMindlin::read_wall(r, out);
  if (r.has("surface_energy")) out.set("surface_energy", read_surface_energy(r));
}

Jkr::Params Jkr::pair_params(const ContactConfig& contact, const SpeciesConfig& reference) {
  return {HertzMindlin::pair_params(contact, reference), contact.parameters.at("surface_energy")};
}

Jkr::Params Jkr::wall_params(const Params& pair, const ContactParameters& wall, double friction) {
  return {HertzMindlin::wall_params(pair.material, wall, friction), wall.get("surface_energy", pair.surface_energy)};
}

std::optional<ParameterProblem> Jkr::species_problem(const std::vector<SpeciesConfig>& species) {
  return HertzMindlin::material_problem(species, name);
}

BinaryContact Jkr::binary_contact(const Params& p, const HeadOnImpact& impact) {
  if (!(impact.speed > 0.0)) return {kNever, 0.0};  // at rest they stick
  // A case asks for a few impacts many times (derive, checks, `check`): each is integrated once.
  using Key = std::array<double, 7>;
  static std::mutex mutex;
  static std::map<Key, BinaryContact> known;
  const Key key{p.material.e_star,     p.material.g_star,       p.material.damping, p.surface_energy,
                impact.effective_mass, impact.effective_radius, impact.speed};
  {
    const std::lock_guard<std::mutex> lock(mutex);
    if (const auto it = known.find(key); it != known.end()) return it->second;
  }
  const BinaryContact b = integrate_impact(p, impact);
  const std::lock_guard<std::mutex> lock(mutex);
  known.emplace(key, b);
  return b;
}

BinaryContact Jkr::integrate_impact(const Params& p, const HeadOnImpact& impact) {
  // Velocity Verlet on the overlap from first touch until the neck breaks. Stuck: once the kinetic
  // energy and the curve's potential U together fall below U at the neck, which the dashpot only
  // lowers, the neck can never be reached (U rises from the well to it).
  const double dt = HertzMindlin::binary_contact(p.material, impact).duration / kImpactSteps;
  const double detach = detach_overlap(p, impact.effective_radius);
  State state{};
  ContactKinematics k;
  k.normal = {1.0, 0.0, 0.0};
  k.effective_mass = impact.effective_mass;
  k.effective_radius = impact.effective_radius;
  double overlap = 0.0, speed = impact.speed, time = 0.0;  // speed: closing, > 0 while approaching
  const double neck_energy = adhesive_energy(p, neck_radius(p, impact.effective_radius), impact.effective_radius);
  auto acceleration = [&] {
    k.overlap = overlap;
    k.normal_velocity = -speed;
    return force(p, state, k, dt).normal / impact.effective_mass;
  };
  double a = acceleration();
  for (long i = 0; i < long{kStuckDurations} * kImpactSteps; ++i) {
    const double half = speed - 0.5 * dt * a;
    const double next = overlap + half * dt;
    if (next <= detach) {
      const double crossing = time + dt * (overlap - detach) / (overlap - next);
      return {crossing, (half - 0.5 * dt * a) / -impact.speed};
    }
    overlap = next;
    speed = half;
    a = acceleration();
    speed -= 0.5 * dt * a;
    time += dt;
    // The force just found the contact radius at this overlap; the state keeps it.
    const double energy =
        0.5 * impact.effective_mass * speed * speed + adhesive_energy(p, state.contact_radius, impact.effective_radius);
    if (energy < neck_energy) return {kNever, 0.0};
  }
  return {kNever, 0.0};
}

double Jkr::equilibrium_radius(const Params& p, double effective_radius) {
  const double w = 2.0 * p.surface_energy;
  return std::cbrt(9.0 * M_PI * w * effective_radius * effective_radius / (2.0 * p.material.e_star));
}

// F(a) = 4 E* a^3 / (3R) - sqrt(8 pi w E* a^3), delta(a) = a^2 / R - sqrt(2 pi w a / E*).
double Jkr::normal_stiffness(const Params& p, double a, double effective_radius) {
  const double e = p.material.e_star, w = 2.0 * p.surface_energy, r = effective_radius;
  const double df_da = 4.0 * e * a * a / r - 1.5 * std::sqrt(8.0 * M_PI * w * e * a);
  const double ddelta_da = 2.0 * a / r - 0.5 * std::sqrt(2.0 * M_PI * w / (e * a));
  return df_da / ddelta_da;
}

double Jkr::bonded_half_period(const Params& p, const HeadOnImpact& pair) {
  if (!(p.surface_energy > 0.0)) return std::numeric_limits<double>::infinity();
  const double a0 = equilibrium_radius(p, pair.effective_radius);
  const double normal = M_PI * std::sqrt(pair.effective_mass / normal_stiffness(p, a0, pair.effective_radius));
  // Two equal solid spheres: 1 / m_t = 1 / m* + R*^2 / I* with the contact arm R = 2 R* and
  // I* = I / 2 = m R^2 / 5 = (2 m*) (2 R*)^2 / 5, so m_t = 2/7 m*.
  const double tangential_mass = 2.0 / 7.0 * pair.effective_mass;
  const double tangential = M_PI * std::sqrt(tangential_mass / (8.0 * p.material.g_star * a0));
  return p.material.friction > 0.0 ? std::min(normal, tangential) : normal;
}

double Jkr::time_step(const Params& p, const HeadOnImpact& pair, int collision_steps) {
  return std::min(HertzMindlin::time_step(p.material, pair, collision_steps),
                  bonded_half_period(p, pair) / collision_steps);
}

double Jkr::sticking_speed(const Params& p, const HeadOnImpact& impact) {
  const double e = p.material.e_star, w = 2.0 * p.surface_energy, r = impact.effective_radius;
  const double snap = std::cbrt(2.0 * M_PI * w * r * r / e);  // a at delta = 0
  const double lost = adhesive_energy(p, neck_radius(p, r), r) - adhesive_energy(p, snap, r);
  return std::sqrt(2.0 * lost / impact.effective_mass);
}

std::vector<CheckLine> Jkr::describe(const Params& p, const HeadOnImpact& impact) {
  std::vector<CheckLine> lines = HertzMindlin::describe(p.material, impact);
  for (auto& line : lines)
    if (line.label.starts_with("e ")) line.label = "e (no adhesion)";
  const BinaryContact b = binary_contact(p, impact);
  lines.push_back(
      {"surface energy",
       fmt::format("{:.6g} J/m^2: pull-off force {:.6g} N, neck breaks at overlap {:.4g} m", p.surface_energy,
                   pull_off_force(p, impact.effective_radius), detach_overlap(p, impact.effective_radius))});
  if (p.surface_energy > 0.0)
    lines.push_back(
        {"bonded pair",
         fmt::format("a0 = {:.4g} m, half period of its oscillations {:.6g} s (the time step resolves it too)",
                     equilibrium_radius(p, impact.effective_radius), bonded_half_period(p, impact))});
  lines.push_back(
      {"adhesive impact", std::isinf(b.duration)
                              ? fmt::format("sticks at {:.6g} m/s (elastic sticking speed {:.6g} m/s)", impact.speed,
                                            sticking_speed(p, impact))
                              : fmt::format("e = {:.6g}, {:.6g} s at {:.6g} m/s (elastic sticking speed {:.6g} m/s)",
                                            b.restitution, b.duration, impact.speed, sticking_speed(p, impact))});
  return lines;
}

// The engine's time loop for this law, without and with rolling resistance, compiled here once
// (dem_engine_impl.hpp).
template class DemEngine<Jkr, false>;
template class DemEngine<Jkr, true>;

}  // namespace grainflow::dem
