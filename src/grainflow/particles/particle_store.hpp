// The particles of a run as a structure of arrays with plain indices. Indices change when the
// engine re-sorts particles for locality; `id` is the permanent name of a particle.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow {

// How a particle moves: integrated from forces, held fixed, or carried by a wall (bumps).
enum class Motion : std::uint8_t { free = 0, frozen = 1, wall_bump = 2 };

struct ParticleStore {
  std::vector<Vec3> position;          // m (wrapped into the box on periodic axes)
  std::vector<Vec3> velocity;          // m/s
  std::vector<Vec3> angular_velocity;  // rad/s
  std::vector<Vec3> force;             // N
  std::vector<Vec3> torque;            // N m
  std::vector<double> radius;          // m, current (grows during radius expansion)
  std::vector<double> target_radius;   // m, final radius
  std::vector<double> inv_mass;        // 1/kg, 0 for frozen and wall bumps
  std::vector<double> inv_inertia;     // 1/(kg m^2), solid sphere I = 2/5 m r^2
  std::vector<double> mass;            // kg
  std::vector<std::int32_t> species;
  std::vector<std::uint32_t> id;
  std::vector<Motion> motion;
  std::vector<std::int8_t> wall;                   // face index that carries a bump, -1 otherwise
  std::vector<std::array<std::int32_t, 3>> image;  // periodic box crossings, for unwrapped positions
  std::vector<std::uint8_t> ghost;                 // 1: a copy of another MPI rank's particle (not integrated here)

  std::size_t size() const { return position.size(); }
  void resize(std::size_t n);
  // Applies `order` (new index -> old index) to every array; a shorter `order` keeps only those.
  void permute(const std::vector<std::uint32_t>& order);

  // One particle with every field, as bytes can carry it between MPI ranks.
  struct Record {
    Vec3 position, velocity, angular_velocity, force, torque;
    double radius, target_radius, inv_mass, inv_inertia, mass;
    std::array<std::int32_t, 3> image;
    std::int32_t species;
    std::uint32_t id;
    Motion motion;
    std::int8_t wall;
    std::uint8_t ghost;
  };
  Record record(std::size_t i) const;
  void push_back(const Record& r);
  bool moves(std::size_t i) const { return motion[i] == Motion::free; }
  // This rank's own, not a copy of another MPI rank's.
  bool owned(std::size_t i) const { return ghost.empty() || !ghost[i]; }
  // Free and this rank's own: what the observers count.
  bool counted(std::size_t i) const { return motion[i] == Motion::free && owned(i); }

  template <class Archive>  // checkpoints (io/state_archive.hpp)
  void serialize(Archive& ar) {
    ar(position, velocity, angular_velocity, force, torque, radius, target_radius, inv_mass, inv_inertia, mass, species,
       id, motion, wall, image, ghost);
  }
};

}  // namespace grainflow
