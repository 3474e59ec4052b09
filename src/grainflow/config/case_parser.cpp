#include "grainflow/config/case_parser.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "grainflow/config/contact_schema.hpp"
#include "grainflow/config/face_kinds.hpp"
#include "grainflow/config/observer_schema.hpp"
#include "grainflow/config/restitution_laws.hpp"
#include "grainflow/config/rolling_models.hpp"
#include "grainflow/config/wall_conditions.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/config/toml_reader.hpp"
#include "grainflow/config/particle_csv.hpp"
#include "grainflow/config/sampler_tables.hpp"
#include "grainflow/config/flow_tables.hpp"
#include "grainflow/config/wall_tables.hpp"

namespace grainflow {
namespace {

FaceKind parse_face_kind(TomlReader& reader, const std::string& key, const std::string& text) {
  if (const auto kind = face_kind_named(text)) return *kind;
  reader.fail(key, "unknown boundary '" + text + "' (valid: " + face_kind_names() + ")");
}

void read_boundaries(TomlReader& domain, DomainConfig& out) {
  TomlReader boundary = domain.table("boundary");
  static const char* axes[3] = {"x", "y", "z"};
  for (int axis = 0; axis < 3; ++axis) {
    const toml::node* node = boundary.raw(axes[axis]);
    const std::string key = std::string("boundary.") + axes[axis];
    FaceKind lo = FaceKind::periodic, hi = FaceKind::periodic;
    if (!node) {
      domain.fail(key, "is required (" + face_kind_names(" or ") + ")");
    } else if (auto s = node->as_string()) {
      lo = hi = parse_face_kind(domain, key, s->get());
    } else if (auto a = node->as_array(); a && a->size() == 2 && a->get(0)->is_string() && a->get(1)->is_string()) {
      lo = parse_face_kind(domain, key, a->get(0)->as_string()->get());
      hi = parse_face_kind(domain, key, a->get(1)->as_string()->get());
    } else {
      domain.fail(key, "expected a string or [lo_face, hi_face]");
    }
    if ((lo == FaceKind::periodic) != (hi == FaceKind::periodic))
      domain.fail(key, "periodic must apply to both faces of an axis");
    out.faces[axis * 2] = lo;
    out.faces[axis * 2 + 1] = hi;
  }
  boundary.reject_unknown_keys();
}

int face_index(TomlReader& reader, const std::string& key, const std::string& name) {
  for (int f = 0; f < 6; ++f)
    if (name == kFaceNames[f]) return f;
  reader.fail(key, "unknown face '" + name + "' (valid: xlo, xhi, ylo, yhi, zlo, zhi)");
}

// [engine]
void read_engine(TomlReader& top, CaseConfig& c) {
  TomlReader r = top.table("engine");
  c.engine.kind = r.string("kind", c.engine.kind);
  c.engine.dimension = static_cast<int>(r.integer("dimension", c.engine.dimension));
  if (c.engine.kind != "dem" && c.engine.kind != "edmd") r.fail("kind", "must be \"dem\" or \"edmd\"");
  if (c.engine.dimension != 2 && c.engine.dimension != 3) r.fail("dimension", "must be 2 or 3");
  r.reject_unknown_keys();
}

// [domain]
void read_domain(TomlReader& top, CaseConfig& c) {
  TomlReader r = top.table("domain");
  if (!top.has("domain")) top.fail("domain", "is required");
  c.domain.lo = r.required_vec3("lo");
  c.domain.hi = r.required_vec3("hi");
  for (int axis = 0; axis < 3; ++axis)
    if (!(c.domain.hi[axis] > c.domain.lo[axis])) r.fail("hi", "must exceed lo on every axis");
  read_boundaries(r, c.domain);
  r.reject_unknown_keys();
}

// [gravity]
void read_gravity(TomlReader& top, CaseConfig& c) {
  TomlReader r = top.table("gravity");
  c.gravity = r.vec3("vector", c.gravity);
  r.reject_unknown_keys();
}

// [[species]]
void read_species(TomlReader& top, CaseConfig& c) {
  auto entries = top.array_of_tables("species");
  if (entries.empty()) top.fail("species", "at least one [[species]] table is required");
  for (auto& r : entries) {
    SpeciesConfig s;
    s.name = r.string("name", "");
    if (s.name.empty()) r.fail("name", "is required and must not be empty");
    for (const auto& other : c.species)
      if (other.name == s.name) r.fail("name", "species '" + s.name + "' is defined twice");
    s.diameter = r.required_number("diameter");
    if (!(s.diameter > 0.0)) r.fail("diameter", "must be positive");
    s.density = r.required_number("density");
    if (!(s.density > 0.0)) r.fail("density", "must be positive");
    s.count = r.integer("count", 0);
    if (s.count < 0) r.fail("count", "must not be negative");
    s.frozen = r.boolean("frozen", false);
    s.youngs_modulus = r.number("youngs_modulus", 0.0);
    if (s.youngs_modulus < 0.0) r.fail("youngs_modulus", "must be positive");
    s.poisson_ratio = r.number("poisson_ratio", -1.0);
    if (r.has("poisson_ratio") && !(s.poisson_ratio >= 0.0 && s.poisson_ratio < 0.5))
      r.fail("poisson_ratio", "must lie in [0, 0.5)");
    if (s.youngs_modulus > 0.0 && s.poisson_ratio < 0.0) s.poisson_ratio = 0.3;
    if (r.has("position")) {
      s.position = r.required_vec3("position");
      if (s.count != 1) r.fail("position", "places one particle: the species needs count = 1");
    }
    if (r.has("region_lo") != r.has("region_hi"))
      r.fail(r.has("region_lo") ? "region_hi" : "region_lo",
             "a species' placement region needs both region_lo and region_hi");
    if (r.has("region_lo")) {
      if (c.engine.kind != "dem") r.fail("region_lo", "a species' own placement region is a dem feature");
      if (s.position) r.fail("region_lo", "a species placed at its `position` has no region");
      s.region_lo = r.required_vec3("region_lo");
      s.region_hi = r.required_vec3("region_hi");
    }
    r.reject_unknown_keys();
    c.species.push_back(s);
  }
}

// [particles]
void read_particles(TomlReader& top, CaseConfig& c) {
  TomlReader r = top.table("particles");
  auto& p = c.particles;
  p.init = r.string("init", p.init);
  if (p.init != "random" && p.init != "lattice" && p.init != "file")
    r.fail("init", "must be \"random\", \"lattice\" or \"file\"");
  p.file = r.string("file", "");
  if (p.init == "file" && p.file.empty()) r.fail("file", "is required when init = \"file\"");
  if (p.init != "file" && !p.file.empty()) r.fail("file", "is only used with init = \"file\"");
  p.initial_temperature = r.number("initial_temperature", 0.0);
  if (p.initial_temperature < 0.0) r.fail("initial_temperature", "must not be negative");
  const std::int64_t seed = r.integer("seed", 1);
  if (seed < 0) r.fail("seed", "must not be negative");
  p.seed = static_cast<std::uint64_t>(seed);
  if (r.has("region_lo")) p.region_lo = r.vec3("region_lo", {});
  if (r.has("region_hi")) p.region_hi = r.vec3("region_hi", {});
  if (r.has("expansion_time")) {
    p.expansion_time = r.number("expansion_time", p.expansion_time);
    if (p.expansion_time < 0.0) r.fail("expansion_time", "must not be negative");
  }
  p.lattice = r.string("lattice", p.lattice);
  if (p.lattice != "cubic" && p.lattice != "fcc") r.fail("lattice", "must be \"cubic\" or \"fcc\"");
  if (p.lattice == "fcc" && (c.engine.kind != "edmd" || c.engine.dimension != 3))
    r.fail("lattice", "fcc is available for the 3D event-driven engine");
  p.lattice_jitter = r.number("lattice_jitter", 0.0);
  if (!(p.lattice_jitter >= 0.0 && p.lattice_jitter < 1.0)) r.fail("lattice_jitter", "must lie in [0, 1)");
  p.initial_velocity = r.vec3("initial_velocity", {});
  p.initial_profile = r.string("initial_profile", p.initial_profile);
  if (p.initial_profile != "uniform" && p.initial_profile != "couette" && p.initial_profile != "campbell_chute")
    r.fail("initial_profile", "must be \"uniform\", \"couette\" or \"campbell_chute\"");
  p.lattice_spacing = r.number("lattice_spacing", p.lattice_spacing);
  if (!(p.lattice_spacing >= 1.0)) r.fail("lattice_spacing", "must be at least 1 (in diameters)");
  r.reject_unknown_keys();
}

// [contact]'s rolling resistance, for every law.
void read_rolling_resistance(TomlReader& r, ContactConfig& k) {
  k.rolling_friction = r.number("rolling_friction", 0.0);
  if (!(k.rolling_friction >= 0.0 && k.rolling_friction <= 1.0))
    r.fail("rolling_friction", "must lie in [0, 1] (the torque's lever arm is mu_r R*)");
  const bool rolling = k.rolling_friction > 0.0;
  k.rolling_model = r.registered_name("rolling_model", rolling_model_named, rolling ? "epsd" : "none");
  if (rolling && k.rolling_model == "none") r.fail("rolling_model", "is \"none\" but rolling_friction is given");
  if (!r.has("rolling_friction") && k.rolling_model != "none") r.fail("rolling_model", "needs rolling_friction > 0");
  for (const char* key : {"rolling_damping", "rolling_stiffness"})
    if (r.has(key) && k.rolling_model != "epsd") r.fail(key, "belongs to rolling_model = \"epsd\"");
  const double damping = r.number("rolling_damping", k.rolling_damping);
  if (!(damping >= 0.0 && damping <= 1.0)) r.fail("rolling_damping", "must lie in [0, 1] (1 is critical)");
  const double stiffness = r.number("rolling_stiffness", k.rolling_stiffness);
  if (!(stiffness > 0.0)) r.fail("rolling_stiffness", "must be positive");
  if (!rolling) {  // rolling_friction = 0 (e.g. --set) switches a case's model off
    k.rolling_model = "none";
    return;
  }
  k.rolling_damping = damping;
  k.rolling_stiffness = stiffness;
}

// [contact] (DEM): the law by its schema
void read_contact(TomlReader& top, CaseConfig& c, ContactSchemas schemas) {
  if (c.engine.kind == "dem") {
    if (top.has("collision")) top.fail("collision", "is for engine.kind = \"edmd\"; the DEM engine takes [contact]");
    TomlReader r = top.table("contact");
    auto& k = c.contact;
    k.model = r.string("model", std::string(schemas.front().name));
    const ContactSchema* law = find_schema(schemas, k.model);
    if (!law) r.fail("model", "unknown contact model '" + k.model + "' (valid: " + schema_names(schemas) + ")");
    k.friction = r.number("friction", 0.0);
    if (k.friction < 0.0) r.fail("friction", "must not be negative");
    read_rolling_resistance(r, k);
    reject_other_laws_keys(r, schemas, *law, &ContactSchema::keys);
    law->read(r, k.parameters);
    r.reject_unknown_keys();
  }
}

// [collision] (event-driven)
void read_collision(TomlReader& top, CaseConfig& c) {
  if (c.engine.kind == "edmd") {
    if (top.has("contact"))
      top.fail("contact", "is for engine.kind = \"dem\"; the event-driven engine takes [collision]");
    TomlReader r = top.table("collision");
    auto& k = c.collision;
    k.restitution = r.number("restitution", k.restitution);
    if (!(k.restitution >= 0.0 && k.restitution <= 1.0)) r.fail("restitution", "must lie in [0, 1]");
    k.restitution_law = r.registered_name("restitution_law", restitution_law_named, k.restitution_law);
    k.velocity_scale = r.number("velocity_scale", 0.0);
    if (k.velocity_scale < 0.0) r.fail("velocity_scale", "must not be negative");
    // Campbell's listing rolls a particle whose wall rebound is below 1e-4 sqrt(g R); without a
    // threshold a particle resting on a wall under gravity bounces ever faster until time stalls.
    const double g = norm(c.gravity);
    k.rolling_speed = r.number("rolling_speed", g > 0.0 ? 1e-4 * std::sqrt(g * 0.5 * c.species.front().diameter) : 0.0);
    if (k.rolling_speed < 0.0) r.fail("rolling_speed", "must not be negative");
    // Under gravity a particle pressed onto a rolling one would otherwise meet it ever more gently at
    // one instant; the TC model (elastic within contact_duration) keeps them apart. 1e-4 sqrt(R/g).
    k.contact_duration =
        r.number("contact_duration", g > 0.0 ? 1e-4 * std::sqrt(0.5 * c.species.front().diameter / g) : 0.0);
    if (k.contact_duration < 0.0) r.fail("contact_duration", "must not be negative");
    k.separation_gap = r.number("separation_gap", 0.0);
    if (!(k.separation_gap >= 0.0 && k.separation_gap < 0.01))
      r.fail("separation_gap", "must lie in [0, 0.01) (Campbell's listings: 1e-5, centres 2.00001 R apart)");
    if (k.separation_gap > 0.0 && top.has("lees_edwards"))
      r.fail("separation_gap",
             "is not available with Lees-Edwards boundaries (a shifted particle may cross the sliding seam)");
    k.elastic_speed = r.number("elastic_speed", 0.0);
    if (k.elastic_speed < 0.0) r.fail("elastic_speed", "must not be negative");
    if (r.has("roughness") && r.has("tangential_restitution"))
      r.fail("tangential_restitution", "give either roughness or tangential_restitution, not both");
    const std::string roughness = r.string("roughness", "smooth");
    if (roughness != "smooth" && roughness != "rough") r.fail("roughness", "must be \"smooth\" or \"rough\"");
    k.tangential_restitution = r.number("tangential_restitution", roughness == "rough" ? 0.0 : -1.0);
    if (!(k.tangential_restitution >= -1.0 && k.tangential_restitution <= 1.0))
      r.fail("tangential_restitution", "must lie in [-1, 1]");
    k.wall_restitution = r.number("wall_restitution", k.restitution);
    if (!(k.wall_restitution >= 0.0 && k.wall_restitution <= 1.0)) r.fail("wall_restitution", "must lie in [0, 1]");
    k.inertia_factor = r.number("inertia_factor", c.engine.dimension == 2 ? 0.5 : 0.4);
    if (!(k.inertia_factor > 0.0 && k.inertia_factor <= 1.0)) r.fail("inertia_factor", "must lie in (0, 1]");
    r.reject_unknown_keys();
  }
}

// [servo]
void read_servo(TomlReader& top, CaseConfig& c) {
  if (top.has("servo")) {
    TomlReader r = top.table("servo");
    auto& v = c.servo;
    v.enabled = true;
    v.normal_stress = r.required_number("normal_stress");
    if (!(v.normal_stress > 0.0)) r.fail("normal_stress", "must be positive");
    v.keep_shear_rate = r.boolean("keep_shear_rate", true);
    v.shear_rate_walls = r.string("shear_rate_walls", v.shear_rate_walls);
    if (v.shear_rate_walls != "both" && v.shear_rate_walls != "top")
      r.fail("shear_rate_walls",
             "must be \"both\" (symmetric about the walls' mean velocity) or \"top\" (listing COL002)");
    v.scale_width = r.boolean("scale_width", true);
    v.every_collisions = r.integer("every_collisions", 0);
    if (v.every_collisions < 0) r.fail("every_collisions", "must not be negative");
    v.gap_change = r.number("gap_change", 0.0);
    if (v.gap_change < 0.0) r.fail("gap_change", "must not be negative");
    v.interval = r.number("interval", 0.0);
    if (v.interval < 0.0) r.fail("interval", "must not be negative");
    if (c.domain.faces[2] != FaceKind::wall || c.domain.faces[3] != FaceKind::wall)
      r.fail("normal_stress", "the servo moves the walls at ylo and yhi: both must be \"wall\"");
    if (!c.domain.periodic(0)) r.fail("scale_width", "the Couette cell needs a periodic x axis (the flow direction)");
    if (c.walls[3].velocity == c.walls[2].velocity)
      top.fail("walls.yhi.velocity",
               "the Couette servo needs the walls to move relative to each other (U_T sets its units)");
    r.reject_unknown_keys();
  }
}

// [lees_edwards]
void read_lees_edwards(TomlReader& top, CaseConfig& c) {
  if (top.has("lees_edwards")) {
    TomlReader r = top.table("lees_edwards");
    c.lees_edwards_rate = r.required_number("shear_rate");
    if (c.lees_edwards_rate == 0.0)
      r.fail("shear_rate", "must not be zero (drop [lees_edwards] for a plain periodic box)");
    if (!c.domain.periodic(0) || !c.domain.periodic(1))
      r.fail("shear_rate", "Lees–Edwards boundaries need periodic x (flow) and y (gradient) axes");
    r.reject_unknown_keys();
  }
}

// [drive]
void read_drive(TomlReader& top, CaseConfig& c) {
  if (top.has("drive")) {
    TomlReader r = top.table("drive");
    auto& d = c.drive;
    d.enabled = true;
    d.preset = r.string("preset", "");
    if (!d.preset.empty() && d.preset != "rotary") r.fail("preset", "unknown preset (valid: rotary)");
    // A [[geometry]] wall that follows the drive takes it alone unless a face is named too.
    const bool geometry_driven =
        std::any_of(c.geometry.begin(), c.geometry.end(), [](const GeometryConfig& g) { return g.motion.drive; });
    d.face = geometry_driven && !r.has("face") ? -1 : face_index(r, "face", r.string("face", "ylo"));
    d.amplitude = r.vec3("amplitude", {});
    d.frequency = r.vec3("frequency", {});
    d.phase = r.vec3("phase", {});
    if (d.preset == "rotary") {
      // eq. (4-1-1): one amplitude and frequency on all three axes, phases 0, 2pi/3, 4pi/3.
      if (r.has("phase")) r.fail("phase", "is fixed by preset = \"rotary\"");
      const double a = r.has("amplitude") ? d.amplitude.x : 0.0;
      const double f = r.has("frequency") ? d.frequency.x : 0.0;
      if (!(d.amplitude.x == d.amplitude.y && d.amplitude.y == d.amplitude.z))
        r.fail("amplitude", "the rotary preset needs equal amplitudes on all axes");
      if (!(d.frequency.x == d.frequency.y && d.frequency.y == d.frequency.z))
        r.fail("frequency", "the rotary preset needs equal frequencies on all axes");
      d.amplitude = {a, a, a};
      d.frequency = {f, f, f};
      d.phase = {0.0, 2.0 * M_PI / 3.0, 4.0 * M_PI / 3.0};
    }
    for (int axis = 0; axis < 3; ++axis) {
      if (d.amplitude[axis] < 0.0) r.fail("amplitude", "must not be negative");
      if (d.frequency[axis] < 0.0) r.fail("frequency", "must not be negative");
      if (d.amplitude[axis] > 0.0 && d.frequency[axis] == 0.0)
        r.fail("frequency", "an axis with an amplitude needs a positive frequency");
    }
    d.start = r.number("start", 0.0);
    if (d.start < 0.0) r.fail("start", "must not be negative");
    d.ramp = r.number("ramp", 1.0);
    if (d.ramp < 0.0) r.fail("ramp", "must not be negative");
    const FaceKind kind = d.face >= 0 ? c.domain.faces[d.face] : FaceKind::wall;
    if (kind == FaceKind::periodic)
      r.fail("face", std::string("cannot drive a periodic face (") + kFaceNames[d.face] + ")");
    if (kind == FaceKind::open) r.fail("face", std::string("cannot drive an open face (") + kFaceNames[d.face] + ")");
    r.reject_unknown_keys();
  }
}

// [run]
void read_run(TomlReader& top, CaseConfig& c) {
  TomlReader r = top.table("run");
  auto& run = c.run;
  run.collisions = r.integer("collisions", 0);
  if (run.collisions < 0) r.fail("collisions", "must not be negative");
  if (run.collisions > 0 && c.engine.kind != "edmd")
    r.fail("collisions", "only the event-driven engine counts collisions");
  run.protocol = r.string("protocol", run.protocol);
  if (run.protocol != "continuous" && run.protocol != "campbell")
    r.fail("protocol", "must be \"continuous\" or \"campbell\" (segments of at most segment_collisions collisions)");
  const bool segmented = run.protocol == "campbell";
  if (segmented && c.engine.kind != "edmd")
    r.fail("protocol", "Campbell's segments count collisions: an event-driven (edmd) protocol");
  for (const char* key : {"segment_collisions", "max_segments"})
    if (r.has(key) && !segmented) r.fail(key, "only applies with protocol = \"campbell\"");
  run.segment_collisions = r.integer("segment_collisions", run.segment_collisions);
  if (run.segment_collisions < 1) r.fail("segment_collisions", "must be at least 1");
  run.max_segments = static_cast<int>(r.integer("max_segments", run.max_segments));
  if (run.max_segments < 1) r.fail("max_segments", "must be at least 1");
  run.duration = run.collisions > 0 || segmented ? r.number("duration", 1e300) : r.required_number("duration");
  if (!(run.duration > 0.0)) r.fail("duration", "must be positive");
  if (c.engine.kind == "edmd")
    for (const char* key : {"time_step", "collision_steps", "skin", "halt_overlap", "sort_every", "clog_time"})
      if (r.has(key)) r.fail(key, "is a soft-sphere (dem) setting; the event-driven engine has no time step");
  run.time_step = r.number("time_step", 0.0);
  if (run.time_step < 0.0) r.fail("time_step", "must not be negative (0 = from eq. 2-5-4)");
  run.collision_steps = static_cast<int>(r.integer("collision_steps", run.collision_steps));
  if (run.collision_steps < 1) r.fail("collision_steps", "must be at least 1");
  run.skin = r.number("skin", -1.0);
  if (r.has("skin") && !(run.skin > 0.0)) r.fail("skin", "must be positive");
  run.halt_overlap = r.number("halt_overlap", 0.0);
  if (run.halt_overlap < 0.0) r.fail("halt_overlap", "must not be negative");
  run.clog_time = r.number("clog_time", -1.0);
  if (r.has("clog_time") && run.clog_time < 0.0) r.fail("clog_time", "must not be negative (0 = never)");
  run.sort_every = static_cast<int>(r.integer("sort_every", run.sort_every));
  if (run.sort_every < 0) r.fail("sort_every", "must not be negative");
  r.reject_unknown_keys();
}

// [output]
void read_output(TomlReader& top, CaseConfig& c) {
  TomlReader r = top.table("output");
  auto& o = c.output;
  o.interval = r.number("interval", o.interval);
  if (!(o.interval > 0.0)) r.fail("interval", "must be positive");
  o.snapshot_interval = r.number("snapshot_interval", 0.0);
  if (o.snapshot_interval < 0.0) r.fail("snapshot_interval", "must not be negative");
  o.checkpoint_interval = r.number("checkpoint_interval", 0.0);
  if (o.checkpoint_interval < 0.0) r.fail("checkpoint_interval", "must not be negative");
  o.profile_interval = r.number("profile_interval", 0.0);
  if (o.profile_interval < 0.0) r.fail("profile_interval", "must not be negative");
  o.average_start = r.number("average_start", 0.0);
  if (o.average_start < 0.0) r.fail("average_start", "must not be negative");
  o.average_start_collisions = r.integer("average_start_collisions", 0);
  if (o.average_start_collisions < 0) r.fail("average_start_collisions", "must not be negative");
  if (o.average_start_collisions > 0 && c.engine.kind != "edmd")
    r.fail("average_start_collisions", "only the event-driven engine counts collisions (use average_start)");
  o.collision_stresses = r.boolean("collision_stresses", true);
  if (r.has("collision_stresses") && c.engine.kind != "edmd")
    r.fail("collision_stresses", "only the event-driven engine measures stresses from its collisions");
  o.stresses = r.boolean("stresses", false);
  if (r.has("stresses") && c.engine.kind != "dem")
    r.fail("stresses", "is the soft-sphere engine's; the event-driven engine's are output.collision_stresses");
  o.zone_thickness = r.number("zone_thickness", 0.0);
  if (o.zone_thickness < 0.0) r.fail("zone_thickness", "must not be negative");
  o.bed_gap_fraction = r.number("bed_gap_fraction", o.bed_gap_fraction);
  if (!(o.bed_gap_fraction > 0.0 && o.bed_gap_fraction < 0.74)) r.fail("bed_gap_fraction", "must lie in (0, 0.74)");
  o.bed_surface_fraction = r.number("bed_surface_fraction", o.bed_surface_fraction);
  if (!(o.bed_surface_fraction > 0.0 && o.bed_surface_fraction < 0.74))
    r.fail("bed_surface_fraction", "must lie in (0, 0.74)");
  r.reject_unknown_keys();
}

// The tables of the observers that hand over a schema, each read by its observer's own file.
void read_observer_tables(TomlReader& top, CaseConfig& c, ObserverSchemas schemas) {
  for (const ObserverSchema& schema : schemas) {
    const std::string name(schema.table);
    if (!top.has(name)) continue;
    TomlReader r = top.table(name);
    if (c.engine.kind != schema.engine) top.fail(name, std::string(schema.engine_refusal));
    schema.read(r, c, c.observer_tables.add(name));
    r.reject_unknown_keys();
  }
}

CaseConfig parse(const toml::table& root, const std::string& file, const std::set<std::string>& overridden,
                 ContactSchemas schemas, ObserverSchemas observer_schemas, GeometrySchemas geometry_schemas) {
  CaseConfig c;
  c.path = file;
  TomlReader top(file, &root, "", &overridden);
  read_engine(top, c);
  read_domain(top, c);
  read_gravity(top, c);
  read_species(top, c);
  read_particles(top, c);
  read_contact(top, c, schemas);
  read_collision(top, c);
  read_walls(top, c, schemas);
  read_geometry(top, c, schemas, geometry_schemas);
  read_insertions(top, c);
  read_outlets(top, c);
  read_servo(top, c);
  read_lees_edwards(top, c);
  if (top.has("drive") && c.engine.kind == "edmd")
    top.fail("drive", "vibrating drives are for the DEM engine; event-driven walls move at constant velocity");
  read_drive(top, c);
  read_run(top, c);
  read_output(top, c);
  read_trajectory(top, c);
  read_observer_tables(top, c, observer_schemas);
  read_tracers(top, c);
  read_coarse_grain(top, c);
  top.reject_unknown_keys();
  return c;
}

void read_initial_particles(CaseConfig& c, const std::filesystem::path& base_dir) {
  std::filesystem::path file(c.particles.file);
  if (file.is_relative()) file = base_dir / file;
  c.particles.file = file.string();
  if (!std::filesystem::exists(file))
    throw InputError(c.path, "particles.file", "file '" + file.string() + "' does not exist");
  c.initial_particles = io::read_particle_csv(file.string());
  for (auto& species : c.species) {
    if (species.count != 0)
      throw InputError(c.path, "species.count",
                       "species '" + species.name + "': counts come from particles.file with init = \"file\"");
  }
  // Bumps of bumpy faces are rebuilt from the case; a final_state.csv that lists them may be reused.
  std::erase_if(c.initial_particles, [&](const InitialParticle& p) {
    for (int f = 0; f < 6; ++f)
      if (c.domain.faces[f] == FaceKind::bumpy && p.species == std::string("bump_") + kFaceNames[f]) return true;
    return false;
  });
  for (const auto& p : c.initial_particles) {
    auto it =
        std::find_if(c.species.begin(), c.species.end(), [&](const SpeciesConfig& s) { return s.name == p.species; });
    if (it == c.species.end())
      throw InputError(c.particles.file, "species", "particle of unknown species '" + p.species + "'");
    ++it->count;
  }
}

toml::table parse_toml(const std::string& text, const std::string& label) {
  try {
    return toml::parse(text, label);
  } catch (const toml::parse_error& e) {
    std::ostringstream where;
    where << "line " << e.source().begin.line << ", column " << e.source().begin.column;
    throw InputError(label, "", "TOML syntax error at " + where.str() + ": " + std::string(e.description()));
  }
}

}  // namespace

std::string read_case_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the case file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

CaseConfig parse_case(const std::string& text, const std::string& label, const std::vector<std::string>& overrides,
                      ContactSchemas schemas, ObserverSchemas observer_schemas, GeometrySchemas geometry_schemas) {
  toml::table root = parse_toml(text, label);
  std::set<std::string> overridden;
  for (const auto& assignment : overrides) overridden.insert(apply_override(root, assignment, label));
  CaseConfig c = parse(root, label, overridden, schemas, observer_schemas, geometry_schemas);
  c.overrides = overrides;
  if (c.particles.init == "file") read_initial_particles(c, std::filesystem::path(label).parent_path());
  return c;
}

}  // namespace grainflow
