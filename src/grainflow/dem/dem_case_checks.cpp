// The checks of a soft-sphere case that combine several keys: dimension, the law's parameters,
// steps per contact, periodic lengths against the cell grid, bumpy lattices, what fits where,
// output intervals. Throws InputError naming the key.
#include "grainflow/dem/dem_case_checks.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "grainflow/config/case_checks.hpp"
#include "grainflow/config/face_kinds.hpp"
#include "grainflow/core/ball_measure.hpp"
#include "grainflow/dem/bump_lattice.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/walls/wall_types.hpp"
#include "grainflow/dem/dem_state.hpp"
#include "grainflow/dem/neighbor_list.hpp"

namespace grainflow::dem {
namespace {

using case_checks::fail;
using case_checks::fmt_number;

// Minimum steps per binary contact: below ~5 velocity Verlet misses the spring's turning point
// badly (it goes unstable at dt = 2/omega, i.e. ~1.6 steps per contact).
constexpr double kMinStepsPerContact = 5.0;
// Random placement with radius expansion cannot reach dense packings; 0.5 leaves room to expand.
constexpr double kMaxRandomSolidsFraction = 0.5;
// A coarse-graining cell's sums: mass, volume, momentum, sum m v v, contact stress (20 doubles).
constexpr double kCoarseGrainBytesPerCell = 20 * 8;

// Discs (2D) move in the x-y plane: nothing may push them off it.
void validate_planar(const CaseConfig& c) {
  if (c.domain.faces[4] != FaceKind::periodic || c.domain.faces[5] != FaceKind::periodic)
    fail(c, "domain.boundary", "in 2D (discs in the x-y plane) z must be \"periodic\": there are no walls along z");
  if (c.gravity.z != 0.0) fail(c, "gravity.vector", "in 2D (discs in the x-y plane) the z component must be 0");
  if (c.drive.enabled && c.drive.amplitude.z != 0.0)
    fail(c, "drive.amplitude", "in 2D (discs in the x-y plane) the z component must be 0");
  if (c.particles.initial_velocity.z != 0.0)
    fail(c, "particles.initial_velocity", "in 2D (discs in the x-y plane) the z component must be 0");
  for (int f = 0; f < 4; ++f) {
    const std::string wall = std::string("walls.") + kFaceNames[f];
    if (c.walls[f].velocity.z != 0.0)
      fail(c, wall + ".velocity", "in 2D (discs in the x-y plane) the z component must be 0");
    if (c.domain.faces[f] == FaceKind::bumpy && c.walls[f].lattice == "triangular")
      fail(c, wall + ".lattice", "in 2D a bumpy wall is one row of half-discs: \"triangular\" has no meaning");
  }
  // A wall of any shape keeps every contact normal in the plane: a plane's normal in it, a
  // cylinder's axis across it (a circle), a cone not at all; it moves in the plane, turns about z.
  for (std::size_t g = 0; g < c.geometry.size(); ++g) {
    const GeometryConfig& geometry = c.geometry[g];
    const std::string key = "geometry." + std::to_string(g);
    const std::string why = "in 2D (discs in the x-y plane) ";
    if (const auto problem = walls::in_plane_problem(geometry, 0.5 * (c.domain.lo.z + c.domain.hi.z)))
      fail(c, key + "." + problem->key, why + problem->reason);
    if (geometry.motion.velocity.z != 0.0) fail(c, key + ".motion.velocity", why + "the z component must be 0");
    if (geometry.motion.angular_velocity.x != 0.0 || geometry.motion.angular_velocity.y != 0.0)
      fail(c, key + ".motion.angular_velocity", why + "walls turn about z only");
  }
}

// Lees–Edwards shear (flow x, gradient y): the sliding rows' search needs four cells of one list
// cutoff along x and three along y, and a potential along the sheared axes would have no bound.
void validate_lees_edwards(const CaseConfig& c, const dem::DerivedQuantities& d) {
  if (c.gravity.x != 0.0 || c.gravity.y != 0.0)
    fail(c, "gravity.vector",
         "with Lees-Edwards boundaries gravity may only act along z (x and y are sheared and periodic)");
  if (c.coarse_grain.enabled)
    fail(c, "coarse_grain",
         "is not yet available with Lees-Edwards boundaries (stresses.csv gives the strips' stresses)");
  const double cutoff = d.max_diameter + d.skin + d.cohesion_reach;
  if (c.domain.length(0) < 4.0 * cutoff)
    fail(c, "domain.hi",
         "with Lees-Edwards boundaries the box must be at least 4 list cutoffs (" + fmt_number(4.0 * cutoff) +
             " m: diameter + skin) long along x");
  if (c.domain.length(1) < 3.0 * cutoff)
    fail(c, "domain.hi",
         "with Lees-Edwards boundaries the box must be at least 3 list cutoffs (" + fmt_number(3.0 * cutoff) +
             " m: diameter + skin) high along y");
}

// The Couette servo with soft particles: the flat walls at ylo and yhi are steered along y; the
// periodic width stays, and nothing else may move those walls along y.
void validate_servo(const CaseConfig& c) {
  if (c.servo.scale_width)
    fail(c, "servo.scale_width", "the DEM engine keeps its periodic width: set scale_width = false");
  if (c.drive.enabled && (c.drive.face == 2 || c.drive.face == 3))
    fail(c, "drive.face", "the servo moves the walls at ylo and yhi: a drive may not move them as well");
  for (int f : {2, 3})
    if (c.walls[f].velocity.y != 0.0)
      fail(c, std::string("walls.") + kFaceNames[f] + ".velocity", "the servo sets the walls' speeds along y: give 0");
}

// Every periodic axis long enough for the image search.
void validate_periodic_lengths(const CaseConfig& c, const dem::DerivedQuantities& d) {
  const int dim = c.engine.dimension;
  // A periodic width shorter than two cutoffs is searched for every image within reach, up to
  // kMaxImage box lengths: so at least half a cutoff.
  for (int axis = 0; axis < dim; ++axis) {
    if (!c.domain.periodic(axis)) continue;
    const double needed = (d.max_diameter + d.skin) / PeriodicBox::kMaxImage;
    if (c.domain.length(axis) < needed)
      fail(c, "domain.hi",
           std::string("periodic axis ") + "xyz"[axis] + " is " + std::to_string(c.domain.length(axis)) +
               " m long; it must be at least (largest diameter + skin) / 2 = " + std::to_string(needed) +
               " m (images are searched up to two box lengths away)");
  }
}

// A mesh more than this many particle diameters across would need ~10^10 grains to fill: its file
// is in other units than the case (millimetres read as metres); one smaller than a grain, the reverse.
constexpr double kMaxMeshDiameters = 1e5;

void validate_mesh_sizes(const CaseConfig& c, const dem::DerivedQuantities& d) {
  for (std::size_t g = 0; g < c.geometry.size(); ++g) {
    const walls::WallShape shape = walls::make_wall_shape(c.geometry[g]);
    const auto* mesh = std::get_if<walls::MeshWall>(&shape);
    if (!mesh) continue;
    const Vec3 size = mesh->surface->hi() - mesh->surface->lo();
    const double extent = std::max({size.x, size.y, size.z});
    const std::string file = c.geometry[g].keys.text("file");
    const std::string key = "geometry." + std::to_string(g) + ".scale";
    if (extent > kMaxMeshDiameters * d.max_diameter)
      fail(c, key,
           "the mesh of '" + file + "' spans " + fmt_number(extent) + " m, " + fmt_number(extent / d.max_diameter) +
               " particle diameters: its file is in other units than the case? (scale turns file units into the "
               "case's)");
    if (extent < d.max_diameter)
      fail(c, key,
           "the mesh of '" + file + "' spans " + fmt_number(extent) + " m, less than one particle diameter (" +
               fmt_number(d.max_diameter) + " m): its file is in other units than the case? (scale turns file "
               "units into the case's)");
  }
}

// Bumps that neither overlap nor let the smallest free species through.
void validate_bumpy_walls(const CaseConfig& c) {
  for (int f = 0; f < 6; ++f) {
    if (c.domain.faces[f] != FaceKind::bumpy) continue;
    const dem::BumpLattice lattice = dem::bump_lattice(c, f);
    const std::string key = std::string("walls.") + kFaceNames[f] + ".spacing";
    if (lattice.closest_bumps() < lattice.bump_diameter * (1.0 - 1e-9))
      fail(c, key,
           "bumps would overlap: the lattice (stretched to tile the face: " + std::to_string(lattice.columns) + " x " +
               std::to_string(lattice.rows) + ") puts bump centres " + std::to_string(lattice.closest_bumps()) +
               " m apart, less than bump_diameter");
    double smallest = 0.0;
    for (const auto& s : c.species)
      if (!s.frozen && (smallest == 0.0 || s.diameter < smallest)) smallest = s.diameter;
    if (lattice.largest_passing_diameter() >= smallest)
      fail(c, key,
           "the " + std::string(lattice.triangular ? "triangular" : "square") + " lattice (" +
               std::to_string(lattice.columns) + " x " + std::to_string(lattice.rows) + " bumps) lets spheres up to " +
               std::to_string(lattice.largest_passing_diameter()) + " m through; the smallest species is " +
               std::to_string(smallest) + " m (reduce spacing or enlarge bump_diameter)");
  }
}

// Particles must fit where they are placed: regions, lattice sites, or the file's positions.
void validate_placement(const CaseConfig& c, const dem::DerivedQuantities& d) {
  const int dim = c.engine.dimension;
  if (c.particles.init != "file") {
    Vec3 lo = c.particles.region_lo.value_or(c.domain.lo);
    Vec3 hi = c.particles.region_hi.value_or(c.domain.hi);
    // The species placed at random must fit across the region (one placed at its own `position`,
    // Lan's large sphere, need not).
    // A region (the particles' shared one, or a species' own) must fit what is drawn in it.
    auto check_region = [&](const Vec3& lo, const Vec3& hi, double placed_diameter, double solids,
                            const std::string& key_lo, const std::string& key_hi, const std::string& what) {
      for (int axis = 0; axis < dim; ++axis) {
        if (lo[axis] < c.domain.lo[axis] || hi[axis] > c.domain.hi[axis])
          fail(c, key_lo, "the placement region must lie inside the domain");
        // Along a periodic axis centres go anywhere (no face to keep clear of).
        if (!c.domain.periodic(axis) && !(hi[axis] - lo[axis] > placed_diameter))
          fail(c, key_hi,
               "the placement region must be wider than the largest diameter placed at random on every bounded axis");
        if (!(hi[axis] > lo[axis])) fail(c, key_hi, "the placement region must have a positive extent");
      }
      double volume = 1.0;  // an area in 2D
      for (int axis = 0; axis < dim; ++axis) volume *= hi[axis] - lo[axis];
      if (c.particles.init == "random" && solids / volume > kMaxRandomSolidsFraction)
        fail(c, "species.count",
             "the particles fill " + std::to_string(solids / volume) + " of " + what +
                 "; random placement needs at most " + std::to_string(kMaxRandomSolidsFraction) +
                 " (enlarge the domain or region)");
    };
    double placed_diameter = 0.0, solids = 0.0;
    for (const auto& species : c.species) {
      if (species.region_lo) {
        if (c.particles.init != "random")
          fail(c, "species.region_lo",
               "species '" + species.name + "': a species' own region is for init = \"random\"");
        check_region(*species.region_lo, *species.region_hi, species.diameter,
                     species.count * ball_measure(dim, 0.5 * species.diameter), "species.region_lo",
                     "species.region_hi", "species '" + species.name + "''s placement region");
        continue;
      }
      if (!species.position && species.count > 0) placed_diameter = std::max(placed_diameter, species.diameter);
      solids += species.count * ball_measure(dim, 0.5 * species.diameter);
    }
    check_region(lo, hi, placed_diameter, solids, "particles.region_lo", "particles.region_hi", "the placement region");
    if (c.particles.init == "lattice") {
      const double spacing = c.particles.lattice_spacing * d.max_diameter;
      double sites = 1;  // counted in double: a huge region must not overflow an integer
      for (int axis = 0; axis < dim; ++axis) sites *= std::floor((hi[axis] - lo[axis]) / spacing);
      long total = 0;
      for (const auto& s : c.species) total += s.count;
      if (static_cast<double>(total) > sites)
        fail(c, "species.count",
             std::to_string(total) + " particles do not fit on the " + fmt_number(sites) +
                 " lattice sites of the placement region");
    }
  } else {
    for (std::size_t i = 0; i < c.initial_particles.size(); ++i) {
      const auto& p = c.initial_particles[i];
      for (int axis = 0; axis < dim; ++axis) {
        const bool closed_lo = c.domain.faces[axis * 2] != FaceKind::open && !c.domain.periodic(axis);
        const bool closed_hi = c.domain.faces[axis * 2 + 1] != FaceKind::open && !c.domain.periodic(axis);
        if ((closed_lo && p.position[axis] < c.domain.lo[axis]) || (closed_hi && p.position[axis] > c.domain.hi[axis]))
          throw InputError(c.particles.file, "particle " + std::to_string(i + 1),
                           std::string("lies outside the domain on axis ") + "xyz"[axis]);
      }
    }
  }
}

// A species' fixed start position: with random placement, inside the domain.
void validate_fixed_positions(const CaseConfig& c) {
  const int dim = c.engine.dimension;
  for (const auto& s : c.species)
    if (s.position) {
      if (c.particles.init != "random")
        fail(c, "species.position",
             "species '" + s.name + "': a fixed start position needs particles.init = \"random\"");
      for (int axis = 0; axis < dim; ++axis)
        if ((*s.position)[axis] < c.domain.lo[axis] || (*s.position)[axis] > c.domain.hi[axis])
          fail(c, "species.position", "species '" + s.name + "' starts outside the domain on axis " + "xyz"[axis]);
    }
}

// [tracers]: ids that exist, an interval of at least a step.
void validate_tracers(const CaseConfig& c, const dem::DerivedQuantities& d) {
  if (!c.tracers.enabled) return;
  const long total = d.moving_particles + d.frozen_particles;
  for (auto id : c.tracers.particles)
    if (id >= static_cast<std::uint64_t>(total))
      fail(c, "tracers.particles",
           "there is no particle with id " + std::to_string(id) + " (ids run from 0 to " + std::to_string(total - 1) +
               ")");
  if (c.tracers.interval > 0.0 && c.tracers.interval < d.time_step)
    fail(c, "tracers.interval", "is shorter than one time step");
}

// [coarse_grain]: a grid the kernel resolves and memory holds.
void validate_coarse_grain(const CaseConfig& c, const dem::DerivedQuantities& d) {
  const int dim = c.engine.dimension;
  if (!c.coarse_grain.enabled) return;
  const auto& g = c.coarse_grain;
  const std::string size_key = g.kernel == "lucy" ? "coarse_grain.cutoff" : "coarse_grain.width";
  const double spread = g.standard_deviation(d.reference_diameter, dim);
  const Vec3 length = c.domain.hi - c.domain.lo;
  const std::array<int, 3> cells = g.grid(length, d.reference_diameter, dim);
  if (dim == 2 && cells[2] != 1)
    fail(c, "coarse_grain.cells", "in 2D the grid has one cell along z (the discs' plane): give [nx, ny, 1]");
  double count = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double h = length[a] / cells[a];
    // A kernel narrower than the cells puts each point into the one cell it lies in: binning, not
    // coarse graining.
    const bool averaged =
        cells[a] == 1 && (c.domain.periodic(a) || (dim == 2 && a == 2));  // a profile across that axis
    if (h > 2.0 * spread && !averaged)
      fail(c, "coarse_grain.cells",
           std::string("cells ") + fmt_number(h) + " m wide along " + static_cast<char>('x' + a) +
               " are wider than twice the kernel's standard deviation (" + fmt_number(spread) +
               " m): the kernel is not resolved; use more cells or a wider kernel (" + size_key + ")");
    count *= cells[a];
  }
  const double bytes = count * kCoarseGrainBytesPerCell;
  if (bytes > 4e9)
    fail(c, "coarse_grain.cells",
         "the grid of " + fmt_number(count) + " cells would take " + fmt_number(bytes / 1e9) + " GB; use fewer cells");
  if (g.interval > 0.0 && g.interval < d.time_step) fail(c, "coarse_grain.interval", "is shorter than one time step");
}

// [trajectory]: a window of at least a step, ids that exist, a file of sane size.
void validate_trajectory(const CaseConfig& c, const dem::DerivedQuantities& d) {
  if (!c.trajectory.enabled) return;
  const auto& t = c.trajectory;
  if (t.window > 0.0 && t.window < d.time_step) fail(c, "trajectory.window", "is shorter than one time step");
  const long total = d.moving_particles + d.frozen_particles;
  for (auto id : t.particles)
    if (id >= static_cast<std::uint64_t>(total))
      fail(c, "trajectory.particles",
           "there is no particle with id " + std::to_string(id) + " (ids run from 0 to " + std::to_string(total - 1) +
               ")");
  const double followed = t.particles.empty() ? static_cast<double>(d.moving_particles) : t.particles.size();
  const double bytes = 48.0 * followed * static_cast<double>(t.samples);  // velocity + position, 6 doubles
  if (bytes > 64e9)
    fail(c, "trajectory.samples",
         "trajectory.h5 would hold " + std::to_string(bytes / 1e9) +
             " GB; follow fewer particles or take fewer samples");
}

}  // namespace

DerivedQuantities validate_dem_case(const CaseConfig& c) {
  const int dim = c.engine.dimension;
  if (dim == 2) validate_planar(c);
  visit_contact_law(c.contact.model, [&]<ContactLaw Law>() {
    if (const auto problem = Law::species_problem(c.species)) fail(c, "species." + problem->key, problem->reason);
  });
  const dem::DerivedQuantities d = dem::derive(c);
  if (c.lees_edwards_rate != 0.0) validate_lees_edwards(c, d);
  if (c.servo.enabled) validate_servo(c);
  if (c.particles.initial_profile == "couette" && (!holds_wall(c.domain.faces[2]) || !holds_wall(c.domain.faces[3])))
    fail(c, "particles.initial_profile", "the couette profile needs walls at ylo and yhi");

  if (d.moving_particles + d.frozen_particles == 0 && c.insertions.empty())
    fail(c, "species.count", "no particles to simulate (and no [[insertion]] to put any in)");
  if (d.law_problem) fail(c, "contact." + d.law_problem->key, d.law_problem->reason);
  if (d.steps_per_contact < kMinStepsPerContact) {
    const double suggested = d.contact_duration / kMinStepsPerContact;
    fail(c, d.time_step_from_case ? "run.time_step" : "run.collision_steps",
         "time step " + std::to_string(d.time_step) + " s resolves a contact of " + std::to_string(d.contact_duration) +
             " s in only " + std::to_string(d.steps_per_contact) +
             " steps; use a time step <= " + std::to_string(suggested) + " s (at least 5 steps per contact)");
  }
  validate_periodic_lengths(c, d);
  validate_mesh_sizes(c, d);
  validate_bumpy_walls(c);
  validate_placement(c, d);
  if (c.drive.enabled && c.drive.face >= 0 && c.domain.faces[c.drive.face] == FaceKind::periodic)
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
  validate_fixed_positions(c);
  validate_tracers(c, d);
  validate_coarse_grain(c, d);
  validate_trajectory(c, d);
  return d;
}

// Particles entering and leaving: an outlet some particle can reach; an insertion region inside the
// box, not wholly inside a wall, and able to hold what its rate puts in before they fall out of it.
void validate_flows(const CaseConfig& c, const DemState& s) {
  if ((!c.insertions.empty() || !c.outlets.empty()) && (c.trajectory.enabled || c.tracers.enabled))
    fail(c, c.trajectory.enabled ? "trajectory" : "tracers",
         "follows a fixed set of particles: not yet with [[insertion]] or [[outlet]], which change it");
  for (std::size_t o = 0; o < c.outlets.size(); ++o) {
    const OutletConfig& out = c.outlets[o];
    for (int a = 0; a < 3; ++a)
      if (out.region_hi[a] < c.domain.lo[a] || out.region_lo[a] > c.domain.hi[a])
        fail(c, "outlet." + std::to_string(o) + ".region_lo",
             "the outlet '" + out.name + "' lies outside the box along " + "xyz"[a] + ": no particle can reach it");
  }
  for (std::size_t k = 0; k < c.insertions.size(); ++k) {
    const InsertionConfig& in = c.insertions[k];
    const InsertionRegion& region = s.insertions[k];
    const std::string key = "insertion." + std::to_string(k);
    if (region.inside >= 0 && std::holds_alternative<walls::MeshWall>(s.walls[region.inside].shape))
      fail(c, key + ".inside", "a mesh has no inside: give region_lo and region_hi");
    for (int a = 0; a < 3; ++a)
      if (region.lo[a] < c.domain.lo[a] || region.hi[a] > c.domain.hi[a])
        fail(c, key + ".region_lo", "the insertion '" + in.name + "' reaches outside the box along " + "xyz"[a]);
    // Room: a point of a 9 x 9 x 9 grid over the region clear of every wall by a radius.
    bool room = false;
    for (int i = 0; i < 729 && !room; ++i) {
      Vec3 x;
      const int digits[3] = {i % 9, i / 9 % 9, i / 81};
      for (int a = 0; a < 3; ++a) x[a] = region.lo[a] + (digits[a] + 0.5) / 9.0 * (region.hi[a] - region.lo[a]);
      room = true;
      for (const DemWall& wall : s.walls) room = room && walls::nearest_gap(wall.shape, x, region.radius) >= region.radius;
    }
    if (!room) fail(c, key + ".region_lo", "the insertion '" + in.name + "' lies inside a wall: no room anywhere in it");
    if (in.rate > 0.0) {
      // Random placement fills up to ~30 % of a region; a particle leaves it after falling through
      // its extent along gravity, from the insertion's velocity.
      const double g = norm(c.gravity);
      double volume = 1.0;
      for (int a = 0; a < s.dimension; ++a) volume *= region.hi[a] - region.lo[a];
      const double capacity = 0.3 * volume / ball_measure(s.dimension, region.radius);
      double height = 0.0, speed = 0.0;
      if (g > 0.0) {
        const Vec3 down = c.gravity * (1.0 / g);
        for (int a = 0; a < 3; ++a) height += std::fabs(down[a]) * (region.hi[a] - region.lo[a]);
        speed = std::max(0.0, dot(in.velocity, down));
      }
      const double leave = g > 0.0 ? (std::sqrt(speed * speed + 2.0 * g * height) - speed) / g
                                   : height / std::max(norm(in.velocity), 1e-300);
      if (in.rate * leave > capacity)
        fail(c, key + ".rate",
             "the insertion '" + in.name + "' can hold about " + fmt_number(capacity) + " particles, which fall out of it in " +
                 fmt_number(leave) + " s: at most " + fmt_number(capacity / leave) + " per second, not " +
                 fmt_number(in.rate));
    }
  }
}

}  // namespace grainflow::dem
