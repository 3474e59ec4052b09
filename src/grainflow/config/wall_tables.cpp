#include "grainflow/config/wall_tables.hpp"

#include <algorithm>
#include <string>

#include "grainflow/config/face_kinds.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/config/wall_conditions.hpp"

namespace grainflow {
namespace {

// A wall's material: the contact law's wall keys (restitution for the event-driven engine), its
// friction and rolling friction. [walls.FACE] and [[geometry]] take the same.
void read_wall_material(TomlReader& r, WallConfig& w, const CaseConfig& c, ContactSchemas schemas) {
  const bool edmd = c.engine.kind == "edmd";
  if (edmd) {
    // A hard wall may be perfectly plastic (e = 0).
    w.restitution = r.number("restitution", -1.0);
    if (r.has("restitution") && !(w.restitution >= 0.0 && w.restitution <= 1.0))
      r.fail("restitution", "must lie in [0, 1]");
  } else {
    const ContactSchema& law = *find_schema(schemas, c.contact.model);
    reject_other_laws_keys(r, schemas, law, &ContactSchema::wall_keys);
    law.read_wall(r, w.contact);
  }
  w.friction = r.number("friction", -1.0);
  if (r.has("friction") && w.friction < 0.0) r.fail("friction", "must not be negative");
  w.rolling_friction = r.number("rolling_friction", -1.0);
  if (r.has("rolling_friction")) {
    if (edmd) r.fail("rolling_friction", "is for the DEM engine (contact.rolling_friction)");
    if (!(w.rolling_friction >= 0.0 && w.rolling_friction <= 1.0)) r.fail("rolling_friction", "must lie in [0, 1]");
    if (c.contact.rolling_model == "none") r.fail("rolling_friction", "needs contact.rolling_friction > 0 (the model)");
  }
}

}  // namespace

void reject_other_laws_keys(TomlReader& r, ContactSchemas schemas, const ContactSchema& law,
                            std::span<const std::string_view> ContactSchema::*keys) {
  for (const auto& other : schemas)
    for (std::string_view key : other.*keys) {
      const std::string name(key);
      if (!r.has(name) || std::find(std::begin(law.*keys), std::end(law.*keys), key) != std::end(law.*keys)) continue;
      std::string owners;  // every law that takes it
      for (const auto& owner : schemas)
        if (std::find(std::begin(owner.*keys), std::end(owner.*keys), key) != std::end(owner.*keys))
          owners += (owners.empty() ? "\"" : " or \"") + std::string(owner.name) + "\"";
      r.fail(name, "belongs to contact.model = " + owners + "; \"" + std::string(law.name) + "\" does not take it");
    }
}

void read_geometry(TomlReader& top, CaseConfig& c, ContactSchemas schemas, GeometrySchemas types) {
  if (!top.has("geometry")) return;
  if (c.engine.kind == "edmd")
    top.fail("geometry",
             "the event-driven engine keeps its box faces ([walls]); walls of any shape need engine.kind = \"dem\"");
  std::string names;
  for (const auto& t : types) names += (names.empty() ? "" : ", ") + std::string(t.name);
  for (TomlReader& r : top.array_of_tables("geometry")) {
    GeometryConfig g;
    g.name = r.string("name", "");
    if (g.name.empty()) r.fail("name", "is required (it names the wall in geometry.csv and the snapshots)");
    if (g.name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") != std::string::npos)
      r.fail("name", "'" + g.name + "': use letters, digits, '_' and '-' (it names files)");
    for (const auto& other : c.geometry)
      if (other.name == g.name) r.fail("name", "'" + g.name + "' names two geometries");
    for (const char* face : kFaceNames)
      if (g.name == face) r.fail("name", "'" + g.name + "' is a box face's name");
    if (!r.has("type")) r.fail("type", "is required (registered: " + names + ")");
    g.type = r.string("type", "");
    const GeometrySchema* type = nullptr;
    for (const auto& t : types)
      if (t.name == g.type) type = &t;
    if (!type) r.fail("type", "unknown wall type '" + g.type + "' (registered: " + names + ")");
    try {  // the keys' errors name the geometry too: its index alone is hard to find in a long case
      type->read(r, g.keys);
      read_wall_material(r, g.material, c, schemas);
    } catch (const InputError& e) {
      throw InputError(e.file(), e.key(), "geometry '" + g.name + "' (" + g.type + "): " + e.reason());
    }
    if (r.has("motion")) {
      TomlReader m = r.table("motion");
      g.motion.velocity = m.vec3("velocity", {});
      g.motion.angular_velocity = m.vec3("angular_velocity", {});
      g.motion.origin = m.vec3("origin", {});
      g.motion.drive = m.boolean("drive", false);
      if (g.motion.drive && !top.has("drive")) m.fail("drive", "follows the case's [drive], which is missing");
      m.reject_unknown_keys();
    }
    r.reject_unknown_keys();
    c.geometry.push_back(std::move(g));
  }
}

void read_walls(TomlReader& top, CaseConfig& c, ContactSchemas schemas) {
  TomlReader walls = top.table("walls");
  for (int f = 0; f < 6; ++f) {
    if (!walls.has(kFaceNames[f])) continue;
    TomlReader r = walls.table(kFaceNames[f]);
    WallConfig& w = c.walls[f];
    const bool edmd = c.engine.kind == "edmd";
    if (r.has("condition") && !edmd) r.fail("condition", "wall conditions are for the event-driven engine");
    w.condition = r.registered_name("condition", wall_condition_named, "smooth");
    read_wall_material(r, w, c, schemas);
    w.velocity = r.vec3("velocity", {});
    w.bump_diameter = r.number("bump_diameter", 0.0);
    if (r.has("bump_diameter") && !(w.bump_diameter > 0.0)) r.fail("bump_diameter", "must be positive");
    w.lattice = r.string("lattice", w.lattice);
    if (w.lattice != "square" && w.lattice != "triangular") r.fail("lattice", "must be \"square\" or \"triangular\"");
    w.spacing = r.number("spacing", 0.0);
    if (r.has("spacing") && !(w.spacing > 0.0)) r.fail("spacing", "must be positive");
    const FaceKind kind = c.domain.faces[f];
    if (kind == FaceKind::periodic || kind == FaceKind::open)
      walls.fail(kFaceNames[f], "face is not a wall (boundary is periodic or open)");
    if (kind != FaceKind::bumpy)
      for (const char* key : {"bump_diameter", "lattice", "spacing"})
        if (r.has(key)) r.fail(key, "only applies to a bumpy face");
    r.reject_unknown_keys();
  }
  walls.reject_unknown_keys();
}

}  // namespace grainflow
