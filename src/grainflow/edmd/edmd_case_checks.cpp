// The checks of an event-driven case that combine several keys: no frozen species, 2D z
// components, periodic lengths, no bumpy faces, the Couette profile's wall, what fits where
// (random packing limits, lattice sites), no overlapping explicit particles. Throws InputError.
#include "grainflow/edmd/edmd_case_checks.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "grainflow/config/case_checks.hpp"
#include "grainflow/config/face_kinds.hpp"

namespace grainflow::edmd {
namespace {

std::string event_driven_kinds() {
  std::string out;
  for (const auto& k : kFaceKinds)
    if (k.event_driven) out += std::string(out.empty() ? "" : ", ") + k.name;
  return out;
}

using case_checks::fail;
using case_checks::fmt_number;

}  // namespace

// Densest packings the event-driven placements reach: random sequential addition jams near 0.547
// (discs) and 0.38 (spheres); stay clear of jamming so placement finishes quickly.
constexpr double kMaxRandomFraction2D = 0.45, kMaxRandomFraction3D = 0.30;

void validate_edmd_case(const CaseConfig& c) {
  const int dim = c.engine.dimension;
  long total = 0;
  double max_diameter = 0.0, solids = 0.0;
  for (const auto& s : c.species) {
    if (s.frozen)
      fail(c, "species.frozen", "frozen species are a DEM feature; the event-driven engine moves every particle");
    total += s.count;
    max_diameter = std::max(max_diameter, s.diameter);
    solids +=
        s.count * (dim == 2 ? M_PI / 4.0 * s.diameter * s.diameter : M_PI / 6.0 * s.diameter * s.diameter * s.diameter);
  }
  if (total == 0) fail(c, "species.count", "no particles to simulate");
  if (total > 200'000'000) fail(c, "species.count", "more than 2e8 particles cannot run on one machine");
  if (dim == 2 && c.gravity.z != 0.0)
    fail(c, "gravity.vector", "in 2D (discs in the x-y plane) the z component must be 0");
  if (dim == 2 && c.particles.initial_velocity.z != 0.0)
    fail(c, "particles.initial_velocity", "in 2D (discs in the x-y plane) the z component must be 0");
  for (int axis = 0; axis < dim; ++axis)
    if (c.domain.periodic(axis) && c.domain.length(axis) < 2.0 * max_diameter)
      fail(c, "domain.hi", std::string("periodic axis ") + "xyz"[axis] + " must be at least two diameters long");
  for (int f = 0; f < 6; ++f)
    if (!face_kind_entry(c.domain.faces[f]).event_driven)
      fail(c, "domain.boundary",
           std::string(face_kind_name(c.domain.faces[f])) + " faces (" + kFaceNames[f] +
               ") are a soft-sphere (DEM) feature; the event-driven engine takes " + event_driven_kinds());
  // Strips thinner than a radius would only split each particle into more pieces (as for dem).
  if (c.output.zone_thickness > 0.0 && c.output.zone_thickness < 0.5 * max_diameter)
    fail(c, "output.zone_thickness", "must be at least the radius of the largest particle");
  if (c.trajectory.enabled) {
    const auto& t = c.trajectory;
    if (t.interval == 0.0 && !(trajectory_start(c) < c.run.duration))
      fail(c, "trajectory.start",
           "the samples would start at " + std::to_string(trajectory_start(c)) +
               " s, not before run.duration: start earlier or set trajectory.interval");
    for (auto id : t.particles)
      if (id >= static_cast<std::uint64_t>(total))
        fail(c, "trajectory.particles",
             "there is no particle with id " + std::to_string(id) + " (ids run from 0 to " + std::to_string(total - 1) +
                 ")");
    const double followed = t.particles.empty() ? static_cast<double>(total) : t.particles.size();
    const double bytes = 72.0 * followed * static_cast<double>(t.samples);  // position, velocity, spin: 9 doubles
    if (bytes > 64e9)
      fail(c, "trajectory.samples",
           "trajectory.h5 would hold " + std::to_string(bytes / 1e9) +
               " GB; follow fewer particles or take fewer samples");
  }
  if (c.particles.initial_profile == "couette" &&
      (c.domain.faces[2] != FaceKind::wall || c.domain.faces[3] != FaceKind::wall))
    fail(c, "particles.initial_profile", "the couette profile needs walls at ylo and yhi");
  if (c.particles.init != "file") {
    const Vec3 lo = c.particles.region_lo.value_or(c.domain.lo), hi = c.particles.region_hi.value_or(c.domain.hi);
    double measure = 1.0;
    for (int axis = 0; axis < dim; ++axis) {
      if (lo[axis] < c.domain.lo[axis] || hi[axis] > c.domain.hi[axis])
        fail(c, "particles.region_lo", "the placement region must lie inside the domain");
      measure *= hi[axis] - lo[axis];
    }
    const double fraction = solids / measure;
    const double limit = dim == 2 ? kMaxRandomFraction2D : kMaxRandomFraction3D;
    if (c.particles.init == "random" && fraction > limit)
      fail(c, "species.count",
           "packing fraction " + std::to_string(fraction) + " in the placement region is above the " +
               std::to_string(limit) + " random placement reaches; use init = \"lattice\"");
    if (c.particles.init == "lattice") {
      const bool fcc = c.particles.lattice == "fcc";
      const double spacing = c.particles.lattice_spacing * max_diameter * (fcc ? std::sqrt(2.0) : 1.0);
      double sites = fcc ? 4 : 1;  // counted in double: a huge region must not overflow an integer
      for (int axis = 0; axis < dim; ++axis) sites *= std::floor((hi[axis] - lo[axis]) / spacing);
      if (static_cast<double>(total) > sites)
        fail(c, "species.count",
             std::to_string(total) + " particles do not fit on the " + fmt_number(sites) +
                 " lattice sites of the placement region");
    }
  }
  // Explicit particles (init = "file") are checked apart in run/case_validation.cpp, with the
  // soft-sphere engine's cell grid.
}

}  // namespace grainflow::edmd
