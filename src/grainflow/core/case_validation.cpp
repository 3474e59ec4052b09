#include "grainflow/core/case_validation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "grainflow/core/error.hpp"
#include "grainflow/dem/bump_lattice.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/dem/neighbor_list.hpp"

namespace grainflow {

namespace {

// Minimum steps per binary contact: below ~5 velocity Verlet misses the spring's turning point
// badly (it goes unstable at dt = 2/omega, i.e. ~1.6 steps per contact).
constexpr double kMinStepsPerContact = 5.0;
// Random placement with radius expansion cannot reach dense packings; 0.5 leaves room to expand.
constexpr double kMaxRandomSolidsFraction = 0.5;
// Simple cubic lattice sites need the spacing of lattice_spacing diameters.

// A count or size for a message: an integer as digits, else in %g form.
std::string fmt_number(double x) {
  char text[64];
  std::snprintf(text, sizeof text, x < 1e15 && x == std::floor(x) ? "%.0f" : "%g", x);
  return text;
}

void fail(const CaseConfig& c, const std::string& key, const std::string& reason) {
  throw InputError(c.path, key, reason);
}

void validate_dem(const CaseConfig& c) {
  if (c.engine.dimension != 3)
    fail(c, "engine.dimension", "the DEM engine simulates spheres in 3D; dimension = 2 is not available yet");
  const dem::DerivedQuantities d = dem::derive(c);

  if (d.moving_particles + d.frozen_particles == 0) fail(c, "species.count", "no particles to simulate");
  if (d.law_problem) fail(c, "contact." + d.law_problem->key, d.law_problem->reason);
  if (d.steps_per_contact < kMinStepsPerContact) {
    const double suggested = d.contact_duration / kMinStepsPerContact;
    fail(c, d.time_step_from_case ? "run.time_step" : "run.collision_steps",
         "time step " + std::to_string(d.time_step) + " s resolves a contact of " +
             std::to_string(d.contact_duration) + " s in only " + std::to_string(d.steps_per_contact) +
             " steps; use a time step <= " + std::to_string(suggested) + " s (at least 5 steps per contact)");
  }
  // The cell grid needs two cells across every periodic axis.
  for (int axis = 0; axis < 3; ++axis) {
    if (!c.domain.periodic(axis)) continue;
    const double needed = 2.0 * (d.max_diameter + d.skin);
    if (c.domain.length(axis) < needed)
      fail(c, "domain.hi", std::string("periodic axis ") + "xyz"[axis] + " is " + std::to_string(c.domain.length(axis)) +
                               " m long; it must be at least 2 (largest diameter + skin) = " + std::to_string(needed) + " m");
  }
  for (int f = 0; f < 6; ++f) {
    if (c.domain.faces[f] != FaceKind::bumpy) continue;
    const dem::BumpLattice lattice = dem::bump_lattice(c, f);
    const std::string key = std::string("walls.") + kFaceNames[f] + ".spacing";
    if (lattice.closest_bumps() < lattice.bump_diameter * (1.0 - 1e-9))
      fail(c, key, "bumps would overlap: the lattice (stretched to tile the face: " + std::to_string(lattice.columns) +
                       " x " + std::to_string(lattice.rows) + ") puts bump centres " +
                       std::to_string(lattice.closest_bumps()) + " m apart, less than bump_diameter");
    double smallest = 0.0;
    for (const auto& s : c.species)
      if (!s.frozen && (smallest == 0.0 || s.diameter < smallest)) smallest = s.diameter;
    if (lattice.largest_passing_diameter() >= smallest)
      fail(c, key, "the " + std::string(lattice.triangular ? "triangular" : "square") + " lattice (" +
                       std::to_string(lattice.columns) + " x " + std::to_string(lattice.rows) + " bumps) lets spheres up to " +
                       std::to_string(lattice.largest_passing_diameter()) + " m through; the smallest species is " +
                       std::to_string(smallest) + " m (reduce spacing or enlarge bump_diameter)");
  }
  // Particles must fit where they are placed.
  if (c.particles.init != "file") {
    Vec3 lo = c.particles.region_lo.value_or(c.domain.lo);
    Vec3 hi = c.particles.region_hi.value_or(c.domain.hi);
    for (int axis = 0; axis < 3; ++axis) {
      if (lo[axis] < c.domain.lo[axis] || hi[axis] > c.domain.hi[axis])
        fail(c, "particles.region_lo", "the placement region must lie inside the domain");
      if (!(hi[axis] - lo[axis] > d.max_diameter))
        fail(c, "particles.region_hi", "the placement region must be wider than the largest diameter on every axis");
    }
    double volume = 1.0;
    for (int axis = 0; axis < 3; ++axis) volume *= hi[axis] - lo[axis];
    double solids = 0.0;
    for (const auto& s : c.species) solids += s.count * M_PI / 6.0 * s.diameter * s.diameter * s.diameter;
    if (c.particles.init == "random" && solids / volume > kMaxRandomSolidsFraction)
      fail(c, "species.count", "the particles fill " + std::to_string(solids / volume) +
                                   " of the placement region; random placement needs at most " +
                                   std::to_string(kMaxRandomSolidsFraction) + " (enlarge the domain or region)");
    if (c.particles.init == "lattice") {
      const double spacing = c.particles.lattice_spacing * d.max_diameter;
      double sites = 1;  // counted in double: a huge region must not overflow an integer
      for (int axis = 0; axis < 3; ++axis) sites *= std::floor((hi[axis] - lo[axis]) / spacing);
      long total = 0;
      for (const auto& s : c.species) total += s.count;
      if (static_cast<double>(total) > sites)
        fail(c, "species.count", std::to_string(total) + " particles do not fit on the " + fmt_number(sites) +
                                     " lattice sites of the placement region");
    }
  } else {
    for (std::size_t i = 0; i < c.initial_particles.size(); ++i) {
      const auto& p = c.initial_particles[i];
      for (int axis = 0; axis < 3; ++axis) {
        const bool closed_lo = c.domain.faces[axis * 2] != FaceKind::open && !c.domain.periodic(axis);
        const bool closed_hi = c.domain.faces[axis * 2 + 1] != FaceKind::open && !c.domain.periodic(axis);
        if ((closed_lo && p.position[axis] < c.domain.lo[axis]) || (closed_hi && p.position[axis] > c.domain.hi[axis]))
          throw InputError(c.particles.file, "particle " + std::to_string(i + 1),
                           std::string("lies outside the domain on axis ") + "xyz"[axis]);
      }
    }
  }
  if (c.drive.enabled && c.domain.faces[c.drive.face] == FaceKind::periodic)
    fail(c, "drive.face", "cannot drive a periodic face");
  if (c.output.snapshot_interval > 0.0 && c.output.snapshot_interval < d.time_step)
    fail(c, "output.snapshot_interval", "must be at least one time step");
  if (c.output.interval < d.time_step) fail(c, "output.interval", "must be at least one time step");
  // A particle may then occupy at most three zones (Lan 1994 section 3.1).
  if (c.output.zone_thickness > 0.0 && c.output.zone_thickness < 0.5 * d.max_diameter)
    fail(c, "output.zone_thickness", "must be at least the radius of the largest particle");
  // Refuse sizes that would exhaust memory rather than start and fail hours later.
  constexpr long kMaxParticles = 200'000'000;
  if (d.moving_particles + d.frozen_particles > kMaxParticles)
    fail(c, "species.count", "more than 2e8 particles cannot run on one machine");
  const double steps = c.run.duration / d.time_step;
  if (steps > 1e13) fail(c, "run.duration", "needs more than 1e13 time steps");
  if (c.zone_series.enabled) {
    const double f = c.drive.enabled ? c.drive.frequency[d.gravity_axis] : 0.0;
    if (c.zone_series.interval == 0.0 && !(f > 0.0))
      fail(c, "zone_series.interval", "needs a value: there is no drive along gravity to take 20 samples per period of");
    const double interval = c.zone_series.interval > 0.0 ? c.zone_series.interval : 1.0 / (20.0 * f);
    if (interval < d.time_step) fail(c, "zone_series.interval", "is shorter than one time step");
  }
  for (const auto& s : c.species)
    if (s.position) {
      if (c.particles.init != "random")
        fail(c, "species.position", "species '" + s.name + "': a fixed start position needs particles.init = \"random\"");
      for (int axis = 0; axis < 3; ++axis)
        if ((*s.position)[axis] < c.domain.lo[axis] || (*s.position)[axis] > c.domain.hi[axis])
          fail(c, "species.position", "species '" + s.name + "' starts outside the domain on axis " + "xyz"[axis]);
    }
  if (c.field.enabled) {
    if (c.field.axis == d.gravity_axis)
      fail(c, "field.axis", "must be a horizontal axis; it is the gravity axis");
    if (c.field.cell > 0.0 && c.field.cell < 0.1 * d.reference_diameter)
      fail(c, "field.cell", "is under a tenth of a diameter: most cells would stay empty");
    const double f = c.drive.enabled ? c.drive.frequency[d.gravity_axis] : 0.0;
    if (c.field.phase_bins > 0 && !(f > 0.0))
      fail(c, "field.phase_bins", "needs a drive along gravity (set phase_bins = 0 for the long-term field only)");
    if (c.field.interval > 0.0 && c.field.interval < d.time_step) fail(c, "field.interval", "is shorter than one time step");
  }
  if (c.tracers.enabled) {
    const long total = d.moving_particles + d.frozen_particles;
    for (auto id : c.tracers.particles)
      if (id >= static_cast<std::uint64_t>(total))
        fail(c, "tracers.particles", "there is no particle with id " + std::to_string(id) + " (ids run from 0 to " +
                                         std::to_string(total - 1) + ")");
    if (c.tracers.interval > 0.0 && c.tracers.interval < d.time_step) fail(c, "tracers.interval", "is shorter than one time step");
  }
  if (c.trajectory.enabled) {
    const auto& t = c.trajectory;
    if (t.window > 0.0 && t.window < d.time_step) fail(c, "trajectory.window", "is shorter than one time step");
    const long total = d.moving_particles + d.frozen_particles;
    for (auto id : t.particles)
      if (id >= static_cast<std::uint64_t>(total))
        fail(c, "trajectory.particles", "there is no particle with id " + std::to_string(id) + " (ids run from 0 to " +
                                            std::to_string(total - 1) + ")");
    const double followed = t.particles.empty() ? static_cast<double>(d.moving_particles) : t.particles.size();
    const double bytes = 48.0 * followed * static_cast<double>(t.samples);  // velocity + position, 6 doubles
    if (bytes > 64e9)
      fail(c, "trajectory.samples", "trajectory.h5 would hold " + std::to_string(bytes / 1e9) +
                                        " GB; follow fewer particles or take fewer samples");
  }
}

// Densest packings the event-driven placements reach: random sequential addition jams near 0.547
// (discs) and 0.38 (spheres); stay clear of jamming so placement finishes quickly.
constexpr double kMaxRandomFraction2D = 0.45, kMaxRandomFraction3D = 0.30;

void validate_edmd(const CaseConfig& c) {
  const int dim = c.engine.dimension;
  long total = 0;
  double max_diameter = 0.0, solids = 0.0;
  for (const auto& s : c.species) {
    if (s.frozen) fail(c, "species.frozen", "frozen species are a DEM feature; the event-driven engine moves every particle");
    total += s.count;
    max_diameter = std::max(max_diameter, s.diameter);
    solids += s.count * (dim == 2 ? M_PI / 4.0 * s.diameter * s.diameter : M_PI / 6.0 * s.diameter * s.diameter * s.diameter);
  }
  if (total == 0) fail(c, "species.count", "no particles to simulate");
  if (total > 200'000'000) fail(c, "species.count", "more than 2e8 particles cannot run on one machine");
  if (dim == 2 && c.gravity.z != 0.0) fail(c, "gravity.vector", "in 2D (discs in the x-y plane) the z component must be 0");
  if (dim == 2 && c.particles.initial_velocity.z != 0.0)
    fail(c, "particles.initial_velocity", "in 2D (discs in the x-y plane) the z component must be 0");
  if (c.servo.enabled && c.walls[3].velocity == c.walls[2].velocity)
    fail(c, "walls.yhi.velocity", "the Couette servo needs the walls to move relative to each other (U_T sets its units)");
  for (int axis = 0; axis < dim; ++axis)
    if (c.domain.periodic(axis) && c.domain.length(axis) < 2.0 * max_diameter)
      fail(c, "domain.hi", std::string("periodic axis ") + "xyz"[axis] + " must be at least two diameters long");
  for (int f = 0; f < 6; ++f)
    if (c.domain.faces[f] == FaceKind::bumpy) fail(c, "domain.boundary", "bumpy walls are a DEM feature");
  // Strips thinner than a radius would only split each particle into more pieces (as for dem).
  if (c.output.zone_thickness > 0.0 && c.output.zone_thickness < 0.5 * max_diameter)
    fail(c, "output.zone_thickness", "must be at least the radius of the largest particle");
  if (c.trajectory.enabled) {
    const auto& t = c.trajectory;
    if (t.interval == 0.0 && !(trajectory_start(c) < c.run.duration))
      fail(c, "trajectory.start", "the samples would start at " + std::to_string(trajectory_start(c)) +
                                      " s, not before run.duration: start earlier or set trajectory.interval");
    for (auto id : t.particles)
      if (id >= static_cast<std::uint64_t>(total))
        fail(c, "trajectory.particles", "there is no particle with id " + std::to_string(id) + " (ids run from 0 to " +
                                            std::to_string(total - 1) + ")");
    const double followed = t.particles.empty() ? static_cast<double>(total) : t.particles.size();
    const double bytes = 72.0 * followed * static_cast<double>(t.samples);  // position, velocity, spin: 9 doubles
    if (bytes > 64e9)
      fail(c, "trajectory.samples", "trajectory.h5 would hold " + std::to_string(bytes / 1e9) +
                                        " GB; follow fewer particles or take fewer samples");
  }
  if (c.particles.initial_profile == "couette" && (c.domain.faces[2] != FaceKind::wall || c.domain.faces[3] != FaceKind::wall))
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
      fail(c, "species.count", "packing fraction " + std::to_string(fraction) + " in the placement region is above the " +
                                   std::to_string(limit) + " random placement reaches; use init = \"lattice\"");
    if (c.particles.init == "lattice") {
      const bool fcc = c.particles.lattice == "fcc";
      const double spacing = c.particles.lattice_spacing * max_diameter * (fcc ? std::sqrt(2.0) : 1.0);
      double sites = fcc ? 4 : 1;  // counted in double: a huge region must not overflow an integer
      for (int axis = 0; axis < dim; ++axis) sites *= std::floor((hi[axis] - lo[axis]) / spacing);
      if (static_cast<double>(total) > sites)
        fail(c, "species.count", std::to_string(total) + " particles do not fit on the " + fmt_number(sites) +
                                     " lattice sites of the placement region");
    }
  } else {
    // Explicit particles must not overlap: hard particles cannot start interpenetrating.
    ParticleStore p;
    p.resize(c.initial_particles.size());
    PeriodicBox box{c.domain.lo, c.domain.hi, {c.domain.periodic(0), c.domain.periodic(1), c.domain.periodic(2)}};
    for (std::size_t i = 0; i < c.initial_particles.size(); ++i) {
      const auto& record = c.initial_particles[i];
      double d = record.diameter;
      for (const auto& s : c.species)
        if (d == 0.0 && s.name == record.species) d = s.diameter;
      p.position[i] = record.position;
      if (dim == 2) p.position[i].z = 0.5 * (c.domain.lo.z + c.domain.hi.z);
      p.target_radius[i] = p.radius[i] = 0.5 * d;
      p.id[i] = static_cast<std::uint32_t>(i);
      box.wrap(p.position[i], p.image[i]);
    }
    dem::CellGrid grid;
    grid.setup(box, max_diameter, p.size());
    grid.bin(p.position);
    dem::NeighborPairs pairs;
    grid.build_pairs(p, box, 0.0, 1, pairs);
    for (std::size_t i = 0; i < p.size(); ++i)
      if (pairs.offsets[i + 1] > pairs.offsets[i])
        throw InputError(c.particles.file, "particles " + std::to_string(i + 1) + " and " +
                                               std::to_string(pairs.partner[pairs.offsets[i]] + 1),
                         "overlap: hard particles must start apart");
  }
}

}  // namespace

// Positions carry about 16 digits: beyond 1e9 diameters across, a contact's overlap (1e-3 d and
// less) would be lost in their rounding.
constexpr double kMaxDomainDiameters = 1e9;

void validate_extent(const CaseConfig& c) {
  double max_diameter = 0.0;
  for (const auto& s : c.species) max_diameter = std::max(max_diameter, s.diameter);
  if (!(max_diameter > 0.0)) return;  // the engines' checks name the species
  for (int axis = 0; axis < 3; ++axis) {
    const double diameters = c.domain.length(axis) / max_diameter;
    if (diameters > kMaxDomainDiameters)
      fail(c, "domain.hi", std::string("the domain is ") + fmt_number(diameters) + " diameters long along " + "xyz"[axis] +
                               "; at most 1e9 (positions would lose the precision contacts need)");
  }
}

void validate_case(const CaseConfig& c) {
  validate_extent(c);
  if (c.engine.kind == "edmd") {
    validate_edmd(c);
    return;
  }
  validate_dem(c);
}

}  // namespace grainflow
