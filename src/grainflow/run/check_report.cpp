#include "grainflow/run/check_report.hpp"

#include <cmath>
#include <fmt/format.h>

#include "grainflow/config/restitution_laws.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/walls/wall_types.hpp"

namespace grainflow::run {

namespace {

// Event-driven cases: what the particles are and how they collide.
void print_edmd_check(const CaseConfig& c, std::ostream& out) {
  const int dim = c.engine.dimension;
  double measure = 1.0, solids = 0.0;
  long total = 0;
  for (int a = 0; a < dim; ++a) measure *= c.domain.length(a);
  out << fmt::format("case {}: valid\n", c.path);
  out << fmt::format("  engine                      edmd (event-driven hard {}), dimension {}\n",
                     dim == 2 ? "discs" : "spheres", dim);
  for (const auto& s : c.species) {
    const double area_or_volume =
        dim == 2 ? M_PI / 4.0 * s.diameter * s.diameter : M_PI / 6.0 * s.diameter * s.diameter * s.diameter;
    solids += s.count * area_or_volume;
    total += s.count;
    out << fmt::format("  species {:<18}  d = {:.6g} m, density = {:.6g} {}, mass = {:.6g} kg, count = {}\n", s.name,
                       s.diameter, s.density, dim == 2 ? "kg/m^2" : "kg/m^3", s.density * area_or_volume, s.count);
  }
  const auto& k = c.collision;
  out << fmt::format("  particles                   {}\n", total);
  out << fmt::format("  packing fraction (box)      {:.6g}\n", solids / measure);
  out << fmt::format("  restitution                 {} ({})\n",
                     restitution_law_named(k.restitution_law) == RestitutionLawKind::campbell
                         ? "campbell law"
                         : fmt::format("{:.6g}", k.restitution),
                     k.restitution_law);
  for (int f = 0; f < 6; ++f) {
    if (c.domain.faces[f] != FaceKind::wall || face_axis(f) >= dim) continue;
    const WallConfig& w = c.walls[f];
    out << fmt::format("  wall {}                    e = {:.6g}, {}, velocity [{:.6g}, {:.6g}, {:.6g}] m/s\n",
                       kFaceNames[f], w.restitution >= 0.0 ? w.restitution : k.wall_restitution, w.condition,
                       w.velocity.x, w.velocity.y, w.velocity.z);
  }
  if (c.servo.enabled)
    out << fmt::format("  Couette servo               target normal stress {:.6g} {}, width {}, shear rate {}\n",
                       c.servo.normal_stress, dim == 2 ? "N/m" : "Pa",
                       c.servo.scale_width ? "follows the gap" : "fixed",
                       c.servo.keep_shear_rate ? "kept" : "not kept");
  if (c.lees_edwards_rate != 0.0)
    out << fmt::format("  Lees-Edwards shear rate     {:.6g} 1/s (image rows slide at {:.6g} m/s)\n",
                       c.lees_edwards_rate, c.lees_edwards_rate * c.domain.length(1));
  out << fmt::format("  tangential restitution      {:.6g}  (-1 smooth, 0 Campbell's rough rule)\n",
                     k.tangential_restitution);
  out << fmt::format("  inertia factor (k/R)^2      {:.6g}\n", k.inertia_factor);
  if (k.elastic_speed > 0.0) out << fmt::format("  elastic below impact speed  {:.6g} m/s\n", k.elastic_speed);
  if (k.contact_duration > 0.0) out << fmt::format("  TC contact duration         {:.6g} s\n", k.contact_duration);
  if (k.rolling_speed > 0.0) out << fmt::format("  rolling below rebound speed {:.6g} m/s\n", k.rolling_speed);
  out << fmt::format("  run                         {:.6g} s{}\n", c.run.duration,
                     c.run.collisions > 0 ? fmt::format(" or {} collisions", c.run.collisions) : "");
}

// Radius expansion: how long, and whether growth outpaces what settles it. A radius grows by at
// most d/2 over the expansion time; faster than sqrt(g d) it throws grains up (the kinetic energy it
// injects is of order m v^2, a bed's potential energy per grain of order m g d), and more than 1 % of
// d per contact duration it drives overlaps the contact law has no time to resolve.
void print_expansion(const CaseConfig& c, const dem::DerivedQuantities& d, double diameter, std::ostream& out) {
  const double t = d.expansion_time;
  out << fmt::format("  radius expansion            {:.6g} s  ({}; = {:.3g} contact durations{})\n", t,
                     c.particles.expansion_time >= 0.0 ? "particles.expansion_time" : "default",
                     d.contact_duration > 0.0 ? t / d.contact_duration : 0.0,
                     d.gravity_magnitude > 0.0 ? fmt::format(", {:.3g} fall times over d",
                                                             t / std::sqrt(2.0 * diameter / d.gravity_magnitude))
                                               : std::string());
  const double growth = t > 0.0 ? 0.5 * diameter / t : INFINITY;  // the fastest a radius grows
  const double per_contact = growth * d.contact_duration / diameter;
  if (per_contact > 0.01)
    out << fmt::format(
        "  warning: radii grow up to {:.3g} d per contact duration: too fast for this stiffness "
        "(raise particles.expansion_time to at least {:.3g} s, or leave it out)\n",
        per_contact, 50.0 * d.contact_duration);
  else if (d.gravity_magnitude > 0.0 && growth > std::sqrt(d.gravity_magnitude * diameter))
    out << fmt::format(
        "  warning: radii grow at up to {:.3g} sqrt(g d): growth will throw grains up (raise "
        "particles.expansion_time to at least {:.3g} s, or leave it out)\n",
        growth / std::sqrt(d.gravity_magnitude * diameter), 0.5 * diameter / std::sqrt(d.gravity_magnitude * diameter));
}

}  // namespace

// Each [[geometry]] wall: its type and keys, and how it moves; a turning wall's Froude number
// w^2 R / g about its axis where the type has a radius (a drum's regime, Mellmann 2001).
void print_geometry(const CaseConfig& c, std::ostream& out) {
  for (const GeometryConfig& g : c.geometry) {
    std::string keys;
    for (const GeometryKey& k : g.keys.entries()) {
      keys += (keys.empty() ? "" : ", ") + k.key + " = ";
      if (k.kind == GeometryKey::Kind::vector) keys += fmt::format("[{:.6g}, {:.6g}, {:.6g}]", k.value.x, k.value.y, k.value.z);
      else if (k.kind == GeometryKey::Kind::boolean) keys += k.value.x != 0.0 ? "true" : "false";
      else if (k.kind == GeometryKey::Kind::text) keys += k.text;
      else keys += fmt::format("{:.6g}", k.value.x);
    }
    out << fmt::format("  geometry {:<19} {}: {}\n", g.name, g.type, keys);
    const walls::WallShape shape = walls::make_wall_shape(g);
    if (const auto* mesh = std::get_if<walls::MeshWall>(&shape)) {
      const walls::MeshReport& r = mesh->surface->report();
      const Vec3 size = mesh->surface->hi() - mesh->surface->lo();
      out << fmt::format("{:30}{} triangles ({} STL), {}, {} piece{}, {:.6g} x {:.6g} x {:.6g} m{}\n", "",
                         mesh->surface->size(), r.binary ? "binary" : "ASCII", r.closed ? "closed" : "open", r.pieces,
                         r.pieces == 1 ? "" : "s", size.x, size.y, size.z,
                         r.flipped ? fmt::format("; {} triangles turned over to agree with their neighbours", r.flipped)
                                   : std::string());
    }
    const GeometryMotionConfig& m = g.motion;
    if (!m.moves()) continue;
    std::string motion;
    if (m.velocity != Vec3{}) motion += fmt::format("velocity [{:.6g}, {:.6g}, {:.6g}] m/s", m.velocity.x, m.velocity.y, m.velocity.z);
    if (m.drive) motion += std::string(motion.empty() ? "" : ", ") + "follows [drive]";
    if (m.angular_velocity != Vec3{}) {
      motion += fmt::format("{}turning at [{:.6g}, {:.6g}, {:.6g}] rad/s about [{:.6g}, {:.6g}, {:.6g}]",
                            motion.empty() ? "" : ", ", m.angular_velocity.x, m.angular_velocity.y,
                            m.angular_velocity.z, m.origin.x, m.origin.y, m.origin.z);
      const double g_norm = norm(c.gravity);
      if (g.keys.has("radius") && g_norm > 0.0)
        motion += fmt::format(" (Fr = w^2 R / g = {:.4g})",
                              dot(m.angular_velocity, m.angular_velocity) * g.keys.number("radius") / g_norm);
    }
    out << fmt::format("  {:<28}{}\n", "", motion);
  }
}

void print_check(const CaseConfig& c, std::ostream& out) {
  if (c.engine.kind == "edmd") {
    print_edmd_check(c, out);
    return;
  }
  const dem::DerivedQuantities d = dem::derive(c);
  const auto& ref = c.species[d.reference_species];
  out << fmt::format("case {}: valid\n", c.path);
  out << fmt::format("  engine                      dem, {} moving + {} fixed particles\n", d.moving_particles,
                     d.frozen_particles);
  for (const auto& s : c.species)
    out << fmt::format("  species {:<18}  d = {:.6g} m, rho = {:.6g} kg/m^{}, mass = {:.6g} kg, count = {}{}\n", s.name,
                       s.diameter, s.density, c.engine.dimension, s.mass(c.engine.dimension), s.count,
                       s.frozen ? " (frozen)" : "");
  out << fmt::format("  contact model               {}\n", d.model);
  for (const auto& line : d.law_lines) out << fmt::format("  {:<28}{}\n", line.label, line.value);
  out << fmt::format("  contact duration (binary)   {:.6g} s  (reference species '{}', m = {:.6g} kg)\n",
                     d.contact_duration, ref.name, d.reference_mass);
  out << fmt::format(
      "  time step                   {:.6g} s  ({}; n = {:.4g} in eq. 2-5-4, {:.3g} steps per contact)\n", d.time_step,
      d.time_step_from_case ? "from run.time_step" : "eq. 2-5-4", d.collision_steps, d.steps_per_contact);
  out << fmt::format("  steps to run                {:.6g}\n", std::ceil(c.run.duration / d.time_step));
  out << fmt::format("  neighbor skin               {:.6g} m\n", d.skin);
  if (c.particles.init == "random") print_expansion(c, d, ref.diameter, out);
  if (c.drive.enabled) {
    out << fmt::format("  floor peak speed            {:.6g} m/s\n", d.floor_peak_speed);
    out << fmt::format(
        "  expected max floor overlap  {:.4g} m = {:.4g} d  (sphere hitting the floor at its peak speed)\n",
        d.expected_floor_overlap, d.expected_floor_overlap / ref.diameter);
    out << fmt::format("  shaking acceleration Gamma  {:.6g}  (a omega^2 / g along gravity)\n", d.shaking_acceleration);
    out << fmt::format("  boundary fluctuation V_b    {:.6g}  (eq. 4-1-3)\n", d.boundary_fluctuation_velocity);
  }
  if (d.hertz_k1)
    out << fmt::format(
        "  Hertz-equivalent K1         {:.6g} N/m  (eqs. 2-5-5..2-5-9, E = {:.6g} Pa, nu = {:.3g}; K1 / K1_H = "
        "{:.3g})\n",
        *d.hertz_k1, ref.youngs_modulus, ref.poisson_ratio, d.normal_stiffness / *d.hertz_k1);
  out << fmt::format("  mass hold-up m_t            {:.6g}  (eq. 4-1-3)\n", d.mass_holdup);
  print_geometry(c, out);
}

int check_case(const std::string& case_path, const std::vector<std::string>& overrides, std::ostream& out) {
  print_check(load_case(case_path, overrides), out);
  return 0;
}

}  // namespace grainflow::run
