#include "grainflow/config/case_writer.hpp"
#include "grainflow/config/face_kinds.hpp"

#include <filesystem>
#include <fmt/format.h>
#include <sstream>
#include <type_traits>
#include <variant>

namespace grainflow {
namespace {

// Shortest text that reads back to the same double (fmt's "{}"), always a TOML float.
std::string number(double x) {
  std::string text = fmt::format("{}", x);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";  // "n": inf, nan
  return text;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned>(ch));
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

std::string vec(const Vec3& v) {
  std::string out = "[";  // appended piece by piece: GCC 12's -Wrestrict misfires on "[" + std::string&&
  out += number(v.x);
  out += ", ";
  out += number(v.y);
  out += ", ";
  out += number(v.z);
  return out + "]";
}

template <class T, class Format>
std::string list(const std::vector<T>& items, Format format) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + format(items[i]);
  return out + "]";
}

// One `key = value` line; the value already in TOML form.
struct Out {
  std::ostringstream text;
  void table(const std::string& name) { text << "\n[" << name << "]\n"; }
  void key(const std::string& k, const std::string& value) { text << k << " = " << value << '\n'; }
  void key(const std::string& k, double value) { key(k, number(value)); }
  void key(const std::string& k, long long value) { key(k, std::to_string(value)); }
  void key(const std::string& k, int value) { key(k, std::to_string(value)); }
  void key(const std::string& k, bool value) { key(k, std::string(value ? "true" : "false")); }
  void key(const std::string& k, const char* value) { key(k, quoted(value)); }
  void text_key(const std::string& k, const std::string& value) { key(k, quoted(value)); }
};

void write_domain(Out& o, const CaseConfig& c) {
  o.table("domain");
  o.key("lo", vec(c.domain.lo));
  o.key("hi", vec(c.domain.hi));
  std::string boundary = "{ ";
  for (int axis = 0; axis < 3; ++axis)
    boundary += std::string(axis ? ", " : "") + "xyz"[axis] + " = [" +
                quoted(face_kind_name(c.domain.faces[2 * axis])) + ", " +
                quoted(face_kind_name(c.domain.faces[2 * axis + 1])) + "]";
  o.key("boundary", boundary + " }");
}

void write_species(Out& o, const CaseConfig& c) {
  for (const auto& s : c.species) {
    o.text << "\n[[species]]\n";
    o.text_key("name", s.name);
    o.key("diameter", s.diameter);
    o.key("density", s.density);
    // With init = "file" the counts come from the file (the loader requires 0 here).
    o.key("count", static_cast<long long>(c.particles.init == "file" ? 0 : s.count));
    o.key("frozen", s.frozen);
    o.key("youngs_modulus", s.youngs_modulus);
    if (s.poisson_ratio >= 0.0) o.key("poisson_ratio", s.poisson_ratio);
    if (s.position) o.key("position", vec(*s.position));
    if (s.region_lo) o.key("region_lo", vec(*s.region_lo));
    if (s.region_hi) o.key("region_hi", vec(*s.region_hi));
  }
}

void write_particles(Out& o, const CaseConfig& c) {
  const auto& p = c.particles;
  o.table("particles");
  o.text_key("init", p.init);
  // Absolute, so the resolved case works from the output folder.
  if (p.init == "file") o.text_key("file", std::filesystem::absolute(p.file).lexically_normal().string());
  o.key("initial_temperature", p.initial_temperature);
  o.key("seed", static_cast<long long>(p.seed));
  if (p.region_lo) o.key("region_lo", vec(*p.region_lo));
  if (p.region_hi) o.key("region_hi", vec(*p.region_hi));
  if (p.expansion_time >= 0.0) o.key("expansion_time", p.expansion_time);
  o.key("lattice_spacing", p.lattice_spacing);
  o.text_key("lattice", p.lattice);
  o.key("lattice_jitter", p.lattice_jitter);
  o.key("initial_velocity", vec(p.initial_velocity));
  o.text_key("initial_profile", p.initial_profile);
}

void write_contact(Out& o, const ContactConfig& k) {
  o.table("contact");
  o.text_key("model", k.model);
  o.key("friction", k.friction);
  if (k.rolling_model != "none") {
    o.text_key("rolling_model", k.rolling_model);
    o.key("rolling_friction", k.rolling_friction);
    if (k.rolling_model == "epsd") {
      o.key("rolling_damping", k.rolling_damping);
      o.key("rolling_stiffness", k.rolling_stiffness);
    }
  }
  for (const auto& [key, value] : k.parameters.entries()) o.key(key, value);
}

void write_collision(Out& o, const CollisionConfig& k) {
  o.table("collision");
  o.key("restitution", k.restitution);
  o.text_key("restitution_law", k.restitution_law);
  o.key("velocity_scale", k.velocity_scale);
  o.key("elastic_speed", k.elastic_speed);
  o.key("rolling_speed", k.rolling_speed);
  o.key("contact_duration", k.contact_duration);
  if (k.separation_gap > 0.0) o.key("separation_gap", k.separation_gap);
  o.key("tangential_restitution", k.tangential_restitution);  // stands for `roughness` too
  o.key("wall_restitution", k.wall_restitution);
  o.key("inertia_factor", k.inertia_factor);
}

void write_walls(Out& o, const CaseConfig& c) {
  const bool edmd = c.engine.kind == "edmd";
  for (int f = 0; f < 6; ++f) {
    const FaceKind kind = c.domain.faces[f];
    if (kind == FaceKind::periodic || kind == FaceKind::open) continue;
    const WallConfig& w = c.walls[f];
    o.table(std::string("walls.") + kFaceNames[f]);
    if (edmd) o.text_key("condition", w.condition);
    if (edmd && w.restitution >= 0.0) o.key("restitution", w.restitution);
    for (const auto& [key, value] : w.contact.entries()) o.key(key, value);
    if (w.friction >= 0.0) o.key("friction", w.friction);
    if (!edmd && w.rolling_friction >= 0.0) o.key("rolling_friction", w.rolling_friction);
    o.key("velocity", vec(w.velocity));
    if (kind == FaceKind::bumpy) {
      if (w.bump_diameter > 0.0) o.key("bump_diameter", w.bump_diameter);
      o.text_key("lattice", w.lattice);
      if (w.spacing > 0.0) o.key("spacing", w.spacing);
    }
  }
}

void write_flows(Out& o, const CaseConfig& c) {
  for (const InsertionConfig& in : c.insertions) {
    o.text << "\n[[insertion]]\n";
    o.text_key("name", in.name);
    o.text_key("species", in.species);
    if (in.rate > 0.0) o.key("rate", in.rate);
    else o.key("count", static_cast<long long>(in.count));
    if (!in.inside.empty()) {
      o.text_key("inside", in.inside);
    } else {
      o.key("region_lo", vec(in.region_lo));
      o.key("region_hi", vec(in.region_hi));
    }
    o.key("velocity", vec(in.velocity));
    o.key("start", in.start);
  }
  for (const OutletConfig& out : c.outlets) {
    o.text << "\n[[outlet]]\n";
    o.text_key("name", out.name);
    o.key("region_lo", vec(out.region_lo));
    o.key("region_hi", vec(out.region_hi));
    if (!out.reinsert.empty()) o.text_key("reinsert", out.reinsert);
    if (out.has_bed) {
      o.key("bed_lo", vec(out.bed_lo));
      o.key("bed_hi", vec(out.bed_hi));
    }
  }
}

void write_geometry(Out& o, const CaseConfig& c) {
  for (const GeometryConfig& g : c.geometry) {
    o.text << "\n[[geometry]]\n";
    o.text_key("name", g.name);
    o.text_key("type", g.type);
    for (const GeometryKey& k : g.keys.entries()) {
      if (k.kind == GeometryKey::Kind::number) o.key(k.key, k.value.x);
      else if (k.kind == GeometryKey::Kind::vector) o.key(k.key, vec(k.value));
      else if (k.kind == GeometryKey::Kind::text) o.text_key(k.key, k.text);
      else o.key(k.key, k.value.x != 0.0);
    }
    for (const auto& [key, value] : g.material.contact.entries()) o.key(key, value);
    if (g.material.friction >= 0.0) o.key("friction", g.material.friction);
    if (g.material.rolling_friction >= 0.0) o.key("rolling_friction", g.material.rolling_friction);
    if (g.motion.moves() || g.motion.origin != Vec3{}) {
      o.table("geometry.motion");
      o.key("velocity", vec(g.motion.velocity));
      o.key("angular_velocity", vec(g.motion.angular_velocity));
      o.key("origin", vec(g.motion.origin));
      o.key("drive", g.motion.drive);
    }
  }
}

void write_optional_tables(Out& o, const CaseConfig& c) {
  if (c.servo.enabled) {
    const auto& v = c.servo;
    o.table("servo");
    o.key("normal_stress", v.normal_stress);
    o.key("keep_shear_rate", v.keep_shear_rate);
    o.text_key("shear_rate_walls", v.shear_rate_walls);
    o.key("scale_width", v.scale_width);
    o.key("every_collisions", v.every_collisions);
    o.key("gap_change", v.gap_change);
    if (v.interval > 0.0) o.key("interval", v.interval);
  }
  if (c.lees_edwards_rate != 0.0) {
    o.table("lees_edwards");
    o.key("shear_rate", c.lees_edwards_rate);
  }
  if (c.drive.enabled) {
    const auto& d = c.drive;
    o.table("drive");
    o.text_key("preset", d.preset);
    if (d.face >= 0) o.text_key("face", kFaceNames[d.face]);
    o.key("amplitude", vec(d.amplitude));
    o.key("frequency", vec(d.frequency));
    if (d.preset != "rotary") o.key("phase", vec(d.phase));  // the preset fixes the phases
    o.key("start", d.start);
    o.key("ramp", d.ramp);
  }
}

void write_run(Out& o, const CaseConfig& c) {
  const auto& r = c.run;
  o.table("run");
  o.key("duration", r.duration);
  if (c.engine.kind == "edmd") {
    o.key("collisions", r.collisions);
    o.text_key("protocol", r.protocol);
    if (r.protocol == "campbell") {
      o.key("segment_collisions", r.segment_collisions);
      o.key("max_segments", r.max_segments);
    }
    return;
  }
  o.key("time_step", r.time_step);
  o.key("collision_steps", r.collision_steps);
  if (r.skin > 0.0) o.key("skin", r.skin);
  o.key("halt_overlap", r.halt_overlap);
  if (r.clog_time >= 0.0) o.key("clog_time", r.clog_time);
  o.key("sort_every", r.sort_every);
}

void write_output(Out& o, const CaseConfig& c) {
  const auto& x = c.output;
  o.table("output");
  o.key("interval", x.interval);
  o.key("snapshot_interval", x.snapshot_interval);
  o.key("checkpoint_interval", x.checkpoint_interval);
  o.key("profile_interval", x.profile_interval);
  o.key("average_start", x.average_start);
  o.key("zone_thickness", x.zone_thickness);
  o.key("bed_gap_fraction", x.bed_gap_fraction);
  o.key("bed_surface_fraction", x.bed_surface_fraction);
  if (c.engine.kind == "edmd") {
    o.key("average_start_collisions", x.average_start_collisions);
    o.key("collision_stresses", x.collision_stresses);
  } else {
    o.key("stresses", x.stresses);
  }
}

// The tables of observers with their own schema: each key as the observer stored it, in its order.
void write_observer_tables(Out& o, const ObserverTables& tables) {
  for (const auto& [table, parameters] : tables.entries()) {
    o.table(table);
    for (const auto& [key, value] : parameters.entries())
      std::visit(
          [&, &key = key](const auto& v) {
            if constexpr (std::is_same_v<std::decay_t<decltype(v)>, std::string>) o.text_key(key, v);
            else o.key(key, v);
          },
          value);
  }
}

void write_samplers(Out& o, const CaseConfig& c) {
  const auto id_list = [](const std::vector<std::uint32_t>& v) {
    return list(v, [](std::uint32_t i) { return std::to_string(i); });
  };
  if (c.trajectory.enabled) {
    const auto& t = c.trajectory;
    o.table("trajectory");
    if (t.start >= 0.0) o.key("start", t.start);
    o.key("samples", t.samples);
    if (c.engine.kind == "dem") {
      o.key("window", t.window);
      o.key("max_lag", t.max_lag);
    } else {
      o.key("interval", t.interval);
    }
    o.key("particles", t.particles.empty() ? quoted("all") : id_list(t.particles));
  }
  write_observer_tables(o, c.observer_tables);
  if (c.tracers.enabled) {
    const auto& t = c.tracers;
    o.table("tracers");
    if (!t.particles.empty()) o.key("particles", id_list(t.particles));
    if (!t.species.empty()) o.key("species", list(t.species, quoted));
    o.key("start", t.start);
    o.key("interval", t.interval);
  }
  if (c.coarse_grain.enabled) {
    const auto& g = c.coarse_grain;
    o.table("coarse_grain");
    o.text_key("kernel", g.kernel);
    if (g.kernel == "lucy") o.key("cutoff", g.cutoff);
    else o.key("width", g.width);
    if (g.cells[0] > 0) {
      std::string cells("[");  // appended piece by piece: g++ 12 warns (-Wrestrict) on "[" + string&&
      for (std::size_t k = 0; k < 3; ++k) cells.append(k ? ", " : "").append(std::to_string(g.cells[k]));
      o.key("cells", cells.append("]"));
    }
    if (g.start >= 0.0) o.key("start", g.start);
    o.key("interval", g.interval);
  }
}

}  // namespace

std::string write_case_toml(const CaseConfig& c) {
  Out o;
  o.text << "# The case as run: every key with the value used (defaults filled in, --set applied).\n"
         << "# Written by grainflow from " << c.path << "\n";
  for (const auto& assignment : c.overrides) o.text << "#   --set " << assignment << '\n';
  o.table("engine");
  o.text_key("kind", c.engine.kind);
  o.key("dimension", c.engine.dimension);
  write_domain(o, c);
  o.table("gravity");
  o.key("vector", vec(c.gravity));
  write_species(o, c);
  write_particles(o, c);
  if (c.engine.kind == "dem") write_contact(o, c.contact);
  if (c.engine.kind == "edmd") write_collision(o, c.collision);
  write_walls(o, c);
  write_geometry(o, c);
  write_flows(o, c);
  write_optional_tables(o, c);
  write_run(o, c);
  write_output(o, c);
  write_samplers(o, c);
  return o.text.str();
}

}  // namespace grainflow
