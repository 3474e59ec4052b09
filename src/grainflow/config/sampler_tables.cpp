#include "grainflow/config/sampler_tables.hpp"

#include <algorithm>
#include <string>

namespace grainflow {

// The `particles` key's array of particle ids ([trajectory], [tracers]).
std::vector<std::uint32_t> read_particle_ids(TomlReader& r, const toml::array& list) {
  std::vector<std::uint32_t> ids;
  for (const auto& item : list) {
    const auto value = item.value<std::int64_t>();
    if (!value || *value < 0 || *value > 0xFFFFFFFFll) r.fail("particles", "ids must be non-negative integers");
    ids.push_back(static_cast<std::uint32_t>(*value));
  }
  return ids;
}

// The sampling window keys shared by [trajectory] and [zone_series]: start (< 0 when absent: the
// caller's default) and samples, at least `fewest`.
void read_sampling(TomlReader& r, double& start, long long& samples, long long fewest) {
  start = r.number("start", -1.0);
  if (r.has("start") && start < 0.0) r.fail("start", "must not be negative");
  samples = r.integer("samples", samples);
  if (samples < fewest) r.fail("samples", "needs at least " + std::to_string(fewest) + " samples");
  if (samples > 100000000) r.fail("samples", "more than 10^8 samples is surely a mistake");
}

// [trajectory]
void read_trajectory(TomlReader& top, CaseConfig& c) {
  if (top.has("trajectory")) {
    if (c.run.protocol == "campbell")
      top.fail(
          "trajectory",
          "a trajectory spans the whole run; with run.protocol = \"campbell\" each segment starts its averages afresh");
    TomlReader r = top.table("trajectory");
    auto& t = c.trajectory;
    t.enabled = true;
    read_sampling(r, t.start, t.samples, 2);
    if (c.engine.kind == "dem") {  // windowed averages for correlations (Lan)
      if (r.has("interval"))
        r.fail("interval", "is for event-driven runs; a DEM trajectory's samples are `window` apart");
      t.window = r.number("window", 0.0);
      if (t.window < 0.0) r.fail("window", "must not be negative (0 = half a collision time, Lan's t_s)");
      t.max_lag = r.integer("max_lag", 0);
      if (t.max_lag < 0 || t.max_lag >= t.samples) r.fail("max_lag", "must lie in [0, samples) (0 = samples / 2)");
    } else {  // instantaneous states for distributions (Campbell)
      for (const char* key : {"window", "max_lag"})
        if (r.has(key))
          r.fail(key, "is for DEM runs; an event-driven trajectory holds instantaneous states `interval` apart");
      t.interval = r.number("interval", 0.0);
      if (t.interval < 0.0)
        r.fail("interval", "must not be negative (0 = the rest of the run spread over the samples)");
    }
    if (const toml::node* ids = r.raw("particles")) {
      if (const auto* word = ids->as_string()) {
        if (word->get() != "all") r.fail("particles", "must be \"all\" or an array of particle ids");
      } else if (const auto* list = ids->as_array()) {
        t.particles = read_particle_ids(r, *list);
        if (t.particles.empty()) r.fail("particles", "an empty list follows nobody (use \"all\")");
      } else {
        r.fail("particles", "must be \"all\" or an array of particle ids");
      }
    }
    r.reject_unknown_keys();
  }
}

// [tracers]
void read_tracers(TomlReader& top, CaseConfig& c) {
  if (top.has("tracers")) {
    TomlReader r = top.table("tracers");
    auto& t = c.tracers;
    if (c.engine.kind != "dem") top.fail("tracers", "tracer histories are implemented for the DEM engine only");
    t.enabled = true;
    if (const toml::node* ids = r.raw("particles")) {
      const auto* list = ids->as_array();
      if (!list) r.fail("particles", "must be an array of particle ids");
      t.particles = read_particle_ids(r, *list);
    }
    if (const toml::node* names = r.raw("species")) {
      const auto* list = names->as_array();
      if (!list) r.fail("species", "must be an array of species names");
      for (const auto& item : *list) {
        const auto name = item.value<std::string>();
        if (!name) r.fail("species", "must be an array of species names");
        const bool known =
            std::any_of(c.species.begin(), c.species.end(), [&](const SpeciesConfig& s) { return s.name == *name; });
        if (!known) r.fail("species", "no species is named '" + *name + "'");
        t.species.push_back(*name);
      }
    }
    if (t.particles.empty() && t.species.empty()) r.fail("particles", "name particle ids or species to follow");
    t.start = r.number("start", 0.0);
    if (t.start < 0.0) r.fail("start", "must not be negative");
    t.interval = r.number("interval", 0.0);
    if (t.interval < 0.0) r.fail("interval", "must not be negative (0 = 20 samples per drive period)");
    r.reject_unknown_keys();
  }
}

// [coarse_grain]
void read_coarse_grain(TomlReader& top, CaseConfig& c) {
  if (!top.has("coarse_grain")) return;
  TomlReader r = top.table("coarse_grain");
  auto& g = c.coarse_grain;
  if (c.engine.kind != "dem")
    top.fail("coarse_grain",
             "coarse-grained fields are implemented for the DEM engine only (event-driven runs write "
             "strip profiles and stresses.csv)");
  g.enabled = true;
  g.kernel = r.string("kernel", g.kernel);
  if (g.kernel != "gaussian" && g.kernel != "lucy") r.fail("kernel", "must be \"gaussian\" or \"lucy\"");
  if (g.kernel == "gaussian") {
    if (r.has("cutoff"))
      r.fail("cutoff", "belongs to kernel = \"lucy\"; a Gaussian's size is its standard deviation, width");
    g.width = r.number("width", 0.0);
    if (g.width < 0.0) r.fail("width", "must be positive (or 0: half the reference diameter)");
  } else {
    if (r.has("width"))
      r.fail("width", "belongs to kernel = \"gaussian\"; Lucy's kernel is sized by its cutoff radius");
    g.cutoff = r.number("cutoff", 0.0);
    if (g.cutoff < 0.0) r.fail("cutoff", "must be positive (or 0: sqrt(3) reference diameters)");
  }
  if (const toml::node* cells = r.raw("cells")) {
    const auto* list = cells->as_array();
    if (!list || list->size() != 3) r.fail("cells", "must be an array of three cell counts [nx, ny, nz]");
    for (int a = 0; a < 3; ++a) {
      const auto n = (*list)[static_cast<std::size_t>(a)].value<std::int64_t>();
      if (!n || *n < 1 || *n > 100000) r.fail("cells", "each count must be an integer in [1, 100000]");
      g.cells[a] = static_cast<int>(*n);
    }
  }
  g.start = r.number("start", -1.0);
  if (r.has("start") && g.start < 0.0) r.fail("start", "must not be negative");
  g.interval = r.number("interval", 0.0);
  if (g.interval < 0.0) r.fail("interval", "must not be negative (0 = output.profile_interval)");
  r.reject_unknown_keys();
}

}  // namespace grainflow
