// Builds the initial event-driven state: Campbell's perturbed lattice (section 2.8), random
// placement without overlaps, or explicit particles; velocities uniform or on a Couette profile,
// plus random fluctuations; walls with their conditions and restitutions.
#include <algorithm>
#include <cmath>
#include <random>

#include "grainflow/core/error.hpp"
#include "grainflow/config/couette_servo_rule.hpp"
#include "grainflow/config/face_kinds.hpp"
#include "grainflow/config/initial_flow.hpp"
#include "grainflow/config/restitution_laws.hpp"
#include "grainflow/config/species_sequence.hpp"
#include "grainflow/config/wall_conditions.hpp"
#include "grainflow/edmd/edmd_state.hpp"

namespace grainflow::edmd {
namespace {

// Mass of a disc (2D: density per unit area) or a sphere.
double particle_mass(const SpeciesConfig& s, double diameter, int dimension) {
  return dimension == 2 ? s.density * M_PI / 4.0 * diameter * diameter
                        : s.density * M_PI / 6.0 * diameter * diameter * diameter;
}

void add_particle(EdmdState& s, const CaseConfig& c, int species, double diameter, const Vec3& x) {
  ParticleStore& p = s.particles;
  const std::size_t i = p.size();
  p.resize(i + 1);
  const double m = particle_mass(c.species[species], diameter, c.engine.dimension);
  const double r = 0.5 * diameter;
  p.position[i] = x;
  p.radius[i] = p.target_radius[i] = r;
  p.mass[i] = m;
  p.inv_mass[i] = 1.0 / m;
  p.inv_inertia[i] = 1.0 / (c.collision.inertia_factor * m * r * r);
  p.species[i] = species;
  p.id[i] = static_cast<std::uint32_t>(i);
}

// Square (2D) or simple cubic (3D) lattice filled from the gravity side, each site displaced at
// random by up to lattice_jitter of the gap between neighbors (Campbell's perturbed lattice).
void place_lattice(const CaseConfig& c, EdmdState& s, std::mt19937_64& rng) {
  const int dim = c.engine.dimension;
  const Vec3 lo = c.particles.region_lo.value_or(c.domain.lo), hi = c.particles.region_hi.value_or(c.domain.hi);
  double max_diameter = 0.0;
  for (const auto& sp : c.species) max_diameter = std::max(max_diameter, sp.diameter);
  const bool fcc = c.particles.lattice == "fcc";
  const double nearest = c.particles.lattice_spacing * max_diameter;  // nearest-neighbor distance
  const double spacing = fcc ? nearest * std::sqrt(2.0) : nearest;    // cubic cell edge
  int n[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = static_cast<int>(std::floor((hi[a] - lo[a]) / spacing));
  const auto sequence = species_sequence(c, rng);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const double jitter = 0.5 * c.particles.lattice_jitter * (nearest - max_diameter);
  std::size_t placed = 0;
  if (fcc) {  // four sites per cubic cell, filled cell by cell
    static const double basis[4][3] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i)
          for (const auto& b : basis) {
            if (placed >= sequence.size()) return;
            Vec3 x{lo.x + (i + b[0] + 0.25) * spacing, lo.y + (j + b[1] + 0.25) * spacing,
                   lo.z + (k + b[2] + 0.25) * spacing};
            for (int a = 0; a < 3; ++a) x[a] += jitter * unit(rng);
            const int sp = sequence[placed++];
            add_particle(s, c, sp, c.species[sp].diameter, x);
          }
    return;
  }
  const int up = std::fabs(c.gravity.x) > std::fabs(c.gravity.y) ? 0 : 1;  // fill layers along gravity
  const int across = up == 0 ? 1 : 0;
  for (int k = 0; k < n[2] && placed < sequence.size(); ++k)
    for (int layer = 0; layer < n[up] && placed < sequence.size(); ++layer)
      for (int col = 0; col < n[across] && placed < sequence.size(); ++col) {
        Vec3 x;
        x[up] = lo[up] + (layer + 0.5) * spacing;
        if (c.gravity[up] > 0.0) x[up] = hi[up] - (layer + 0.5) * spacing;
        x[across] = lo[across] + (col + 0.5) * spacing;
        x[2] = dim == 3 ? lo[2] + (k + 0.5) * spacing : 0.0;
        for (int a = 0; a < dim; ++a) x[a] += jitter * unit(rng);
        const int sp = sequence[placed++];
        add_particle(s, c, sp, c.species[sp].diameter, x);
      }
}

// Random sequential addition: each particle tries random positions until it overlaps nothing.
void place_random(const CaseConfig& c, EdmdState& s, std::mt19937_64& rng) {
  const int dim = c.engine.dimension;
  const Vec3 lo = c.particles.region_lo.value_or(c.domain.lo), hi = c.particles.region_hi.value_or(c.domain.hi);
  double max_diameter = 0.0;
  for (const auto& sp : c.species) max_diameter = std::max(max_diameter, sp.diameter);
  // A coarse grid of buckets keeps each overlap test local.
  int n[3] = {1, 1, 1};
  for (int a = 0; a < dim; ++a) n[a] = std::max(1, static_cast<int>((hi[a] - lo[a]) / max_diameter));
  std::vector<std::vector<std::uint32_t>> buckets(static_cast<std::size_t>(n[0]) * n[1] * n[2]);
  auto bucket_of = [&](const Vec3& x, int b[3]) {
    for (int a = 0; a < 3; ++a)
      b[a] = a < dim ? std::clamp(static_cast<int>((x[a] - lo[a]) / (hi[a] - lo[a]) * n[a]), 0, n[a] - 1) : 0;
  };
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto sequence = species_sequence(c, rng);
  for (int sp : sequence) {
    const double r = 0.5 * c.species[sp].diameter;
    bool placed = false;
    for (int attempt = 0; attempt < 100000 && !placed; ++attempt) {
      Vec3 x;
      for (int a = 0; a < dim; ++a) {
        const double margin = c.domain.periodic(a) ? 0.0 : r;
        x[a] = lo[a] + margin + unit(rng) * (hi[a] - lo[a] - 2.0 * margin);
      }
      int b[3];
      bucket_of(x, b);
      bool free = true;
      for (int dz = (dim == 3 ? -1 : 0); dz <= (dim == 3 ? 1 : 0) && free; ++dz)
        for (int dy = -1; dy <= 1 && free; ++dy)
          for (int dx = -1; dx <= 1 && free; ++dx) {
            int q[3] = {b[0] + dx, b[1] + dy, b[2] + dz};
            bool skip = false;
            for (int a = 0; a < 3; ++a) {
              if (q[a] >= 0 && q[a] < n[a]) continue;
              if (!c.domain.periodic(a)) skip = true;
              q[a] = (q[a] + n[a]) % n[a];
            }
            if (skip) continue;
            for (std::uint32_t j : buckets[q[0] + n[0] * (q[1] + n[1] * q[2])]) {
              const Vec3 d = s.box.minimum_image(x, s.particles.position[j]);
              const double sum = r + s.particles.radius[j];
              if (norm2(d) < sum * sum) {
                free = false;
                break;
              }
            }
          }
      if (!free) continue;
      add_particle(s, c, sp, c.species[sp].diameter, x);
      buckets[b[0] + n[0] * (b[1] + n[1] * b[2])].push_back(static_cast<std::uint32_t>(s.particles.size() - 1));
      placed = true;
    }
    if (!placed)
      throw InputError(c.path, "species.count", "random placement found no free spot; use init = \"lattice\"");
  }
}

void set_velocities(const CaseConfig& c, EdmdState& s, std::mt19937_64& rng) {
  ParticleStore& p = s.particles;
  const int dim = c.engine.dimension;
  std::normal_distribution<double> gauss(0.0, std::sqrt(c.particles.initial_temperature));
  Vec3 momentum;
  double mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (c.particles.initial_temperature > 0.0)
      for (int a = 0; a < dim; ++a) p.velocity[i][a] = gauss(rng);
    momentum += p.mass[i] * p.velocity[i];
    mass += p.mass[i];
  }
  double height = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) height = std::max(height, p.position[i].y - c.domain.lo.y);
  const InitialFlow flow(c, height);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (c.particles.initial_temperature > 0.0) p.velocity[i] -= momentum * (1.0 / mass);  // fluctuations only
    p.velocity[i] += flow.at(p.position[i]);
  }
}

}  // namespace

EdmdState build_edmd_state(const CaseConfig& c) {
  EdmdState s;
  s.dimension = c.engine.dimension;
  s.box.lo = c.domain.lo;
  s.box.hi = c.domain.hi;
  for (int a = 0; a < 3; ++a) s.box.periodic[a] = a < s.dimension && c.domain.periodic(a);
  s.gravity = c.gravity;
  s.species = c.species;
  RestitutionLaw law;
  law.kind = restitution_law_named(c.collision.restitution_law);
  law.value = c.collision.restitution;
  law.elastic_speed = c.collision.elastic_speed;
  law.velocity_scale = c.collision.velocity_scale;
  if (law.velocity_scale <= 0.0) {
    const double g = norm(c.gravity) > 0.0 ? norm(c.gravity) : 9.81;
    law.velocity_scale = std::sqrt(g * 0.5 * c.species.front().diameter);  // sqrt(g R), Campbell's scale
  }
  s.restitution = law;
  s.tangential_restitution = c.collision.tangential_restitution;
  s.contact_duration = c.collision.contact_duration;
  s.separation_gap = c.collision.separation_gap;
  s.rolling_speed = c.collision.rolling_speed;
  for (int f = 0; f < 6; ++f) {
    if (!holds_wall(c.domain.faces[f]) || face_axis(f) >= s.dimension) continue;
    const WallConfig& w = c.walls[f];
    EdmdWall wall;
    wall.face = f;
    wall.roles = face_roles(f);
    wall.axis = face_axis(f);
    wall.inward = face_is_high(f) ? -1.0 : 1.0;
    wall.position = face_is_high(f) ? c.domain.hi[wall.axis] : c.domain.lo[wall.axis];
    wall.velocity = w.velocity;
    wall.condition = wall_condition_named(w.condition);
    wall.restitution = law;
    wall.restitution.value = w.restitution >= 0.0 ? w.restitution : c.collision.wall_restitution;
    s.walls.push_back(wall);
  }
  const CouetteServoRule servo = CouetteServoRule::from_case(c, s.dimension);
  s.servo = servo.config;
  s.speed_unit = servo.speed_unit;
  s.stress_unit = servo.stress_unit;
  s.lees_edwards_rate = c.lees_edwards_rate;
  std::mt19937_64 rng(c.particles.seed);
  if (c.particles.init == "file") {
    for (const auto& record : c.initial_particles) {
      int sp = 0;
      while (c.species[sp].name != record.species) ++sp;
      Vec3 x = record.position;
      if (s.dimension == 2) x.z = 0.0;
      add_particle(s, c, sp, record.diameter > 0.0 ? record.diameter : c.species[sp].diameter, x);
      s.particles.velocity.back() = record.velocity;
      s.particles.angular_velocity.back() = record.angular_velocity;
    }
  } else if (c.particles.init == "lattice") {
    place_lattice(c, s, rng);
  } else {
    place_random(c, s, rng);
  }
  if (c.particles.init != "file") set_velocities(c, s, rng);
  if (s.dimension == 2)
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
      s.particles.velocity[i].z = 0.0;
      s.particles.angular_velocity[i].x = s.particles.angular_velocity[i].y = 0.0;
    }
  return s;
}

}  // namespace grainflow::edmd
