#include "grainflow/config/flow_tables.hpp"

#include <string>

namespace grainflow {
namespace {

// A name that names files' rows: letters, digits, '_' and '-', unique among `taken`.
template <class Tables>
std::string read_name(TomlReader& r, const Tables& taken, const char* what) {
  const std::string name = r.string("name", "");
  if (name.empty()) r.fail("name", std::string("is required (it names the ") + what + ")");
  if (name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") != std::string::npos)
    r.fail("name", "'" + name + "': use letters, digits, '_' and '-'");
  for (const auto& t : taken)
    if (t.name == name) r.fail("name", "'" + name + "' names two tables");
  return name;
}

// A box: region_lo below region_hi on every axis.
void read_box(TomlReader& r, Vec3& lo, Vec3& hi) {
  lo = r.required_vec3("region_lo");
  hi = r.required_vec3("region_hi");
  for (int a = 0; a < 3; ++a)
    if (!(lo[a] < hi[a])) r.fail("region_hi", "must exceed region_lo on every axis");
}

void refuse_under_edmd(TomlReader& top, const CaseConfig& c, const char* table) {
  if (c.engine.kind == "edmd")
    top.fail(table, "particles entering or leaving need engine.kind = \"dem\" (the event-driven engine keeps its count)");
}

}  // namespace

void read_insertions(TomlReader& top, CaseConfig& c) {
  if (!top.has("insertion")) return;
  refuse_under_edmd(top, c, "insertion");
  for (TomlReader& r : top.array_of_tables("insertion")) {
    InsertionConfig in;
    in.name = read_name(r, c.insertions, "insertion, which an outlet's reinsert names");
    in.species = r.string("species", "");
    bool known = false;
    std::string names;
    for (const auto& s : c.species) {
      known = known || s.name == in.species;
      names += (names.empty() ? "" : ", ") + s.name;
    }
    if (!known) r.fail("species", "'" + in.species + "' is not a [[species]] (" + names + ")");
    if (r.has("count") == r.has("rate")) r.fail("count", "give either count (a total) or rate (particles per second)");
    in.count = r.integer("count", 0);
    in.rate = r.number("rate", 0.0);
    if (r.has("count") && in.count < 0) r.fail("count", "must not be negative (0: only what an outlet sends back)");
    if (r.has("rate") && !(in.rate > 0.0)) r.fail("rate", "must be positive");
    in.inside = r.string("inside", "");
    if (!in.inside.empty()) {
      if (r.has("region_lo") || r.has("region_hi")) r.fail("inside", "give either inside or region_lo and region_hi");
      bool found = false;
      for (const auto& g : c.geometry) found = found || g.name == in.inside;
      if (!found) r.fail("inside", "'" + in.inside + "' is not a [[geometry]] of this case");
    } else {
      read_box(r, in.region_lo, in.region_hi);
    }
    in.velocity = r.vec3("velocity", {});
    in.start = r.number("start", 0.0);
    if (in.start < 0.0) r.fail("start", "must not be negative");
    r.reject_unknown_keys();
    c.insertions.push_back(in);
  }
}

void read_outlets(TomlReader& top, CaseConfig& c) {
  if (!top.has("outlet")) return;
  refuse_under_edmd(top, c, "outlet");
  for (TomlReader& r : top.array_of_tables("outlet")) {
    OutletConfig out;
    out.name = read_name(r, c.outlets, "outlet in discharge.csv");
    read_box(r, out.region_lo, out.region_hi);
    out.reinsert = r.string("reinsert", "");
    if (r.has("bed_lo") || r.has("bed_hi")) {
      out.has_bed = true;
      out.bed_lo = r.required_vec3("bed_lo");
      out.bed_hi = r.required_vec3("bed_hi");
      for (int a = 0; a < 3; ++a)
        if (!(out.bed_lo[a] < out.bed_hi[a])) r.fail("bed_hi", "must exceed bed_lo on every axis");
    }
    if (!out.reinsert.empty()) {
      bool found = false;
      for (const auto& in : c.insertions) found = found || in.name == out.reinsert;
      if (!found) r.fail("reinsert", "'" + out.reinsert + "' is not an [[insertion]] of this case");
    }
    r.reject_unknown_keys();
    c.outlets.push_back(out);
  }
}

}  // namespace grainflow
