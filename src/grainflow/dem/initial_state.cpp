// Builds the initial DEM state from a case: walls and bumps, then particles placed at random with
// radius expansion (section 2.2), on a lattice, or read from a file; initial velocities.
#include <algorithm>
#include <cmath>
#include <random>

#include "grainflow/core/ball_measure.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/config/face_kinds.hpp"
#include "grainflow/config/initial_flow.hpp"
#include "grainflow/config/species_sequence.hpp"
#include "grainflow/dem/bump_lattice.hpp"
#include "grainflow/dem/dem_case_checks.hpp"
#include "grainflow/dem/dem_state.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/dem/neighbor_list.hpp"

namespace grainflow::dem {
namespace {

// The plane discs lie in (2D): the box's mid-z.
double disc_plane(const CaseConfig& c) { return 0.5 * (c.domain.lo.z + c.domain.hi.z); }

void add_particle(ParticleStore& p, int dimension, const SpeciesConfig& species, int species_index, double diameter,
                  const Vec3& position, Motion motion, int wall = -1) {
  const std::size_t i = p.size();
  p.resize(i + 1);
  const double r = 0.5 * diameter;
  const double m = ball_measure(dimension, r) * species.density;
  p.position[i] = position;
  p.radius[i] = r;
  p.target_radius[i] = r;
  p.mass[i] = m;
  const bool moves = motion == Motion::free;
  p.inv_mass[i] = moves ? 1.0 / m : 0.0;
  p.inv_inertia[i] = moves ? 1.0 / (ball_inertia_factor(dimension) * m * r * r) : 0.0;
  p.species[i] = species_index;
  p.id[i] = static_cast<std::uint32_t>(i);
  p.motion[i] = motion;
  p.wall[i] = static_cast<std::int8_t>(wall);
}

void add_walls(const CaseConfig& c, DemState& s) {
  for (int f = 0; f < 6; ++f) {
    const FaceKind kind = c.domain.faces[f];
    if (!holds_wall(kind)) continue;
    const WallConfig& w = c.walls[f];
    DemWall wall;
    wall.face = f;
    wall.roles = face_roles(f);
    wall.axis = face_axis(f);
    wall.inward = face_is_high(f) ? -1.0 : 1.0;
    wall.base_position = face_is_high(f) ? c.domain.hi[wall.axis] : c.domain.lo[wall.axis];
    wall.motion = WallMotion(w.velocity, c.drive.enabled && c.drive.face == f ? &c.drive : nullptr);
    wall.friction = w.friction >= 0.0 ? w.friction : c.contact.friction;
    wall.bumpy = kind == FaceKind::bumpy;
    wall.name = kFaceNames[f];
    walls::PlaneWall plane;  // the face as a plane: zero off its axis, so its distance is exactly x[axis] - position
    plane.point[wall.axis] = wall.base_position;
    plane.normal[wall.axis] = wall.inward;
    wall.initial_shape = plane;
    wall.move_to(0.0);
    s.walls.push_back(wall);
  }
  for (std::size_t g = 0; g < c.geometry.size(); ++g) {
    const GeometryConfig& geometry = c.geometry[g];
    DemWall wall;
    wall.face = -1;
    wall.name = geometry.name;
    wall.geometry = static_cast<int>(g);
    wall.initial_shape = walls::make_wall_shape(geometry);
    wall.motion = WallMotion(geometry.motion.velocity, geometry.motion.drive ? &c.drive : nullptr);
    wall.angular_velocity = geometry.motion.angular_velocity;
    wall.initial_origin = geometry.motion.origin;
    wall.turns = !std::visit(
        [&](const auto& shape) { return shape.spins_in_place(wall.angular_velocity, wall.initial_origin); },
        wall.initial_shape);
    wall.reach_turn = walls::farthest_corner(c.domain.lo, c.domain.hi, wall.initial_origin);
    wall.friction = geometry.material.friction >= 0.0 ? geometry.material.friction : c.contact.friction;
    wall.move_to(0.0);
    s.walls.push_back(wall);
  }
}

// The first wall of [[geometry]] whose surface a sphere at x of radius r overlaps by more than
// `allowed` of its radius, or null.
const DemWall* geometry_in_the_way(const DemState& s, const Vec3& x, double r, double allowed) {
  for (const DemWall& wall : s.walls)
    if (wall.face < 0 && walls::nearest_gap(wall.shape, x, r) < (1.0 - allowed) * r) return &wall;
  return nullptr;
}

// A particle given a place (a file, a lattice, a species' position) inside a [[geometry]] wall: its
// centre behind the surface or less than half a radius before it (a settled state touches walls by
// a small overlap; a restart from one is fine).
void check_clear_of_geometry(const CaseConfig& c, const DemState& s) {
  const ParticleStore& p = s.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] == Motion::wall_bump) continue;
    if (const DemWall* wall = geometry_in_the_way(s, p.position[i], p.target_radius[i], 0.5))
      throw InputError(c.path, "geometry." + std::to_string(wall->geometry),
                       "particle " + std::to_string(p.id[i]) + " of species '" + c.species[p.species[i]].name +
                           "' at (" + std::to_string(p.position[i].x) + ", " + std::to_string(p.position[i].y) + ", " +
                           std::to_string(p.position[i].z) + ") lies inside the wall '" + wall->name +
                           "': move the particle or the wall");
  }
}

// Fixed half-spheres centred on the wall plane, square or triangular lattice (section 2.6.3).
void add_bumps(const CaseConfig& c, DemState& s) {
  for (const DemWall& wall : s.walls) {
    if (!wall.bumpy) continue;
    const BumpLattice lattice = bump_lattice(c, wall.face);
    SpeciesConfig species;
    species.name = std::string("bump_") + kFaceNames[wall.face];
    species.diameter = lattice.bump_diameter;
    species.density = c.species.front().density;
    species.frozen = true;
    const int species_index = static_cast<int>(s.species.size());
    const int a = lattice.axis_a, b = lattice.axis_b;
    for (int row = 0; row < lattice.rows; ++row) {
      const double offset = lattice.triangular && (row % 2 == 1) ? 0.5 * lattice.column_spacing : 0.0;
      for (int column = 0; column < lattice.columns; ++column) {
        Vec3 x;
        x[wall.axis] = wall.position;
        x[a] = c.domain.lo[a] + (column + 0.5) * lattice.column_spacing + offset;
        x[b] = c.domain.lo[b] + (row + 0.5) * lattice.row_spacing;
        if (x[a] >= c.domain.hi[a]) x[a] -= c.domain.length(a);
        add_particle(s.particles, s.dimension, species, species_index, lattice.bump_diameter, x, Motion::wall_bump,
                     wall.face);
        s.particles.velocity.back() = wall.velocity;
        ++species.count;
      }
    }
    s.species.push_back(species);
  }
}

// Extra distance from a bumpy face: its bumps stand out from the plane by their radius.
double bump_clearance(const CaseConfig& c, int face) {
  if (c.domain.faces[face] != FaceKind::bumpy) return 0.0;
  return 0.5 * bump_lattice(c, face).bump_diameter;
}

Vec3 region_lo(const CaseConfig& c) { return c.particles.region_lo.value_or(c.domain.lo); }
Vec3 region_hi(const CaseConfig& c) { return c.particles.region_hi.value_or(c.domain.hi); }

void place_lattice(const CaseConfig& c, DemState& s, std::mt19937_64& rng, double max_diameter) {
  const Vec3 lo = region_lo(c), hi = region_hi(c);
  const double spacing = c.particles.lattice_spacing * max_diameter;
  int n[3];
  for (int axis = 0; axis < 3; ++axis) n[axis] = static_cast<int>(std::floor((hi[axis] - lo[axis]) / spacing));
  if (s.dimension == 2) n[2] = 1;  // one layer of discs, put on the plane below
  const auto sequence = species_sequence(c, rng);
  // Fill along the axes perpendicular to gravity first, so a bed builds up from the floor.
  const int up = dem::derive(c).gravity_axis;
  const int a = (up + 1) % 3, b = (up + 2) % 3;
  std::size_t placed = 0;
  for (int k = 0; k < n[up] && placed < sequence.size(); ++k)
    for (int jb = 0; jb < n[b] && placed < sequence.size(); ++jb)
      for (int ia = 0; ia < n[a] && placed < sequence.size(); ++ia) {
        Vec3 x;
        x[a] = lo[a] + (ia + 0.5) * spacing;
        x[b] = lo[b] + (jb + 0.5) * spacing;
        const bool down = c.gravity[up] <= 0.0;
        x[up] = down ? lo[up] + (k + 0.5) * spacing : hi[up] - (k + 0.5) * spacing;
        if (s.dimension == 2) x.z = disc_plane(c);
        const int sp = sequence[placed++];
        add_particle(s.particles, s.dimension, c.species[sp], sp, c.species[sp].diameter, x,
                     c.species[sp].frozen ? Motion::frozen : Motion::free);
      }
}

// Random centres (a radius clear of solid faces and bumps), then each radius shrunk to its share of
// the nearest-neighbor distance; radii grow back at one constant rate over `expansion_time` s
// (section 2.2: particles.expansion_time or its default, DerivedQuantities::expansion_time).
void place_random(const CaseConfig& c, double expansion_time, DemState& s, std::mt19937_64& rng) {
  const auto sequence = species_sequence(c, rng);
  const std::size_t first = s.particles.size();
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Others are drawn clear of placed spheres, so those keep their spot and full size.
  std::vector<std::pair<Vec3, double>> placed;
  for (const auto& species : c.species)
    if (species.position) placed.push_back({*species.position, 0.5 * species.diameter});
  auto clear_of_placed = [&](const Vec3& x, double r) {
    for (const auto& [centre, radius] : placed)
      if (norm(s.box.minimum_image(x, centre)) < radius + r) return false;
    return true;
  };
  for (int sp : sequence) {
    Vec3 x;
    const double r = 0.5 * c.species[sp].diameter;
    if (c.species[sp].position) {
      // A placed sphere (Lan's large sphere on the floor): the others are drawn clear of it.
      add_particle(s.particles, s.dimension, c.species[sp], sp, c.species[sp].diameter, *c.species[sp].position,
                   c.species[sp].frozen ? Motion::frozen : Motion::free);
      continue;
    }
    const Vec3 lo = c.species[sp].region_lo.value_or(region_lo(c));
    const Vec3 hi = c.species[sp].region_hi.value_or(region_hi(c));
    long draws = 0;
    do {
      if (++draws > 100000)
        throw InputError(c.path, "species.position", "the placement region has no room left around the placed spheres");
      for (int axis = 0; axis < 3; ++axis) {
        // Keep centres at least a radius inside solid faces of the region (clear of the bumps).
        double margin_lo = 0.0, margin_hi = 0.0;
        if (!c.domain.periodic(axis)) {
          margin_lo = r + bump_clearance(c, axis * 2);
          margin_hi = r + bump_clearance(c, axis * 2 + 1);
        }
        x[axis] = lo[axis] + margin_lo + unit(rng) * (hi[axis] - lo[axis] - margin_lo - margin_hi);
      }
      if (s.dimension == 2) x.z = disc_plane(c);
    } while (!clear_of_placed(x, r) || geometry_in_the_way(s, x, r, 0.0));
    add_particle(s.particles, s.dimension, c.species[sp], sp, c.species[sp].diameter, x,
                 c.species[sp].frozen ? Motion::frozen : Motion::free);
  }
  ParticleStore& p = s.particles;
  double max_radius = 0.0;
  for (std::size_t i = first; i < p.size(); ++i) max_radius = std::max(max_radius, p.target_radius[i]);
  CellGrid grid;
  grid.setup(s.box, 2.0 * max_radius, p.size());
  grid.bin(p.position);
  NeighborPairs near;
  grid.build_pairs(p, s.box, 0.0, 1, near);
  const auto shifts = s.box.shift_table();
  std::vector<double> allowed(p.target_radius);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::uint32_t k = near.offsets[i]; k < near.offsets[i + 1]; ++k) {
      const std::uint32_t j = near.partner[k];
      const double distance = norm(p.position[i] - (p.position[j] + shifts[near.shift[k]]));
      const double ti = p.target_radius[i], tj = p.target_radius[j];
      if (p.motion[i] != Motion::free && p.motion[j] != Motion::free) {
        continue;  // two fixed spheres never interact: a random base may overlap itself
      } else if (p.motion[i] != Motion::free) {
        allowed[j] = std::min(allowed[j], distance - ti);  // a fixed partner does not shrink
      } else if (p.motion[j] != Motion::free) {
        allowed[i] = std::min(allowed[i], distance - tj);
      } else {
        allowed[i] = std::min(allowed[i], distance * ti / (ti + tj));
        allowed[j] = std::min(allowed[j], distance * tj / (ti + tj));
      }
    }
  double largest_deficit = 0.0;
  for (std::size_t i = first; i < p.size(); ++i) {
    p.radius[i] = std::max(allowed[i], 1e-3 * p.target_radius[i]);
    largest_deficit = std::max(largest_deficit, p.target_radius[i] - p.radius[i]);
  }
  if (largest_deficit > 0.0) {
    s.expansion_rate =
        expansion_time > 0.0 ? largest_deficit / expansion_time : std::numeric_limits<double>::infinity();
  }
}

void place_from_file(const CaseConfig& c, DemState& s) {
  for (const auto& record : c.initial_particles) {
    int sp = 0;
    while (c.species[sp].name != record.species) ++sp;
    const double diameter = record.diameter > 0.0 ? record.diameter : c.species[sp].diameter;
    const Motion motion = c.species[sp].frozen ? Motion::frozen : Motion::free;
    add_particle(s.particles, s.dimension, c.species[sp], sp, diameter, record.position, motion);
    s.particles.velocity.back() = record.velocity;
    s.particles.angular_velocity.back() = record.angular_velocity;
  }
}

void thermalise(const CaseConfig& c, DemState& s, std::mt19937_64& rng) {
  if (c.particles.initial_temperature <= 0.0) return;
  ParticleStore& p = s.particles;
  std::normal_distribution<double> gauss(0.0, std::sqrt(c.particles.initial_temperature));
  Vec3 momentum;
  double total_mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] != Motion::free) continue;
    p.velocity[i] = {gauss(rng), gauss(rng), s.dimension == 3 ? gauss(rng) : 0.0};
    momentum += p.mass[i] * p.velocity[i];
    total_mass += p.mass[i];
  }
  if (total_mass == 0.0) return;
  const Vec3 drift = momentum * (1.0 / total_mass);  // no net momentum: T is all fluctuation
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.motion[i] == Motion::free) p.velocity[i] -= drift;
}

// The mean flow the case starts with, as the event-driven engine does (config/initial_flow.hpp).
void add_initial_flow(const CaseConfig& c, DemState& s) {
  ParticleStore& p = s.particles;
  double height = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.motion[i] == Motion::free) height = std::max(height, p.position[i].y - c.domain.lo.y);
  const InitialFlow flow(c, height);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.motion[i] == Motion::free) p.velocity[i] += flow.at(p.position[i]);
}

// Discs keep only their in-plane motion: a z position, z velocity or in-plane spin given in a file
// (or placed, for a species' own position) is put on the plane, as the event-driven engine does.
void confine_to_plane(const CaseConfig& c, DemState& s) {
  ParticleStore& p = s.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.position[i].z = disc_plane(c);
    p.velocity[i].z = 0.0;
    p.angular_velocity[i].x = p.angular_velocity[i].y = 0.0;
  }
}

}  // namespace

DemState build_dem_state(const CaseConfig& c) {
  const DerivedQuantities d = derive(c);
  DemState s;
  s.dimension = c.engine.dimension;
  s.box.lo = c.domain.lo;
  s.box.hi = c.domain.hi;
  for (int axis = 0; axis < 3; ++axis) s.box.periodic[axis] = c.domain.periodic(axis);
  if (s.dimension == 2) s.box.periodic[2] = false;  // the discs' plane: no images along z
  s.box.shear_velocity = c.lees_edwards_rate * c.domain.length(1);
  s.gravity = c.gravity;
  s.time_step = d.time_step;
  s.skin = d.skin;
  s.cohesion_reach = d.cohesion_reach;
  s.species = c.species;
  s.servo = CouetteServoRule::from_case(c, s.dimension);
  add_walls(c, s);
  add_bumps(c, s);
  std::mt19937_64 rng(c.particles.seed);
  if (c.particles.init == "file") {
    place_from_file(c, s);
  } else if (c.particles.init == "lattice") {
    place_lattice(c, s, rng, d.max_diameter);
  } else {
    place_random(c, d.expansion_time, s, rng);
  }
  check_clear_of_geometry(c, s);
  thermalise(c, s, rng);
  if (c.particles.init != "file") add_initial_flow(c, s);
  if (s.dimension == 2) confine_to_plane(c, s);
  for (std::size_t i = 0; i < s.particles.size(); ++i)
    s.box.wrap(s.particles.position[i], s.particles.image[i], &s.particles.velocity[i]);
  for (const InsertionConfig& in : c.insertions) {
    InsertionRegion r;
    for (std::size_t k = 0; k < c.species.size(); ++k)
      if (c.species[k].name == in.species) r.species = static_cast<int>(k);
    const ParticleStore::Record sized = species_particle(c, r.species, Vec3{}, Vec3{});
    r.radius = sized.radius;
    r.mass = sized.mass;
    r.inv_inertia = sized.inv_inertia;
    r.count = in.count;
    r.rate = in.rate;
    r.lo = in.region_lo;
    r.hi = in.region_hi;
    if (!in.inside.empty()) {
      r.lo = c.domain.lo;
      r.hi = c.domain.hi;
      for (std::size_t w = 0; w < s.walls.size(); ++w)
        if (s.walls[w].face < 0 && s.walls[w].name == in.inside) r.inside = static_cast<int>(w);
    }
    if (s.dimension == 2) r.lo.z = r.hi.z = disc_plane(c);
    r.velocity = in.velocity;
    r.start = in.start;
    s.insertions.push_back(r);
  }
  for (const OutletConfig& o : c.outlets) {
    s.outlets.push_back({o.region_lo, o.region_hi});
    int back = -1;
    for (std::size_t k = 0; k < c.insertions.size(); ++k)
      if (c.insertions[k].name == o.reinsert) back = static_cast<int>(k);
    s.reinsert.push_back(back);
  }
  s.exchanges = !c.outlets.empty() || !c.insertions.empty();
  validate_flows(c, s);
  return s;
}

ParticleStore::Record species_particle(const CaseConfig& c, int species, const Vec3& position, const Vec3& velocity) {
  ParticleStore::Record r{};
  const int dimension = c.engine.dimension;
  r.position = position;
  r.velocity = velocity;
  if (dimension == 2) r.position.z = disc_plane(c), r.velocity.z = 0.0;
  r.radius = r.target_radius = 0.5 * c.species[species].diameter;
  r.mass = ball_measure(dimension, r.radius) * c.species[species].density;
  r.inv_mass = 1.0 / r.mass;
  r.inv_inertia = 1.0 / (ball_inertia_factor(dimension) * r.mass * r.radius * r.radius);
  r.species = species;
  r.motion = Motion::free;
  r.wall = -1;
  return r;
}

}  // namespace grainflow::dem
