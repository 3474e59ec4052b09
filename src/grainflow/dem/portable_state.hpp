// A soft-sphere run's state in a form no decomposition shapes: every particle, the touching pairs'
// and particle-wall contacts' states by particle id, the clock and the counters. A checkpoint holds
// it beside the per-rank states, so that a run can continue on another number of MPI ranks (one
// to several, several to one, P to Q). The continuation has the same physics from the same state,
// but not the same bits: the neighbour lists are built afresh at the restart, so forces are summed
// in another order.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "grainflow/core/vec3.hpp"
#include "grainflow/dem/contact_store.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::dem {

// What a restart needs before the engine is built: the particles (to place the sub-domains) and
// the clock.
struct PortableParticles {
  std::vector<ParticleStore::Record> particles;  // every one, by id (forces of the last step included)
  double time = 0.0;
  long step = 0;
  std::array<Vec3, 6> bump_velocity{}, bump_displacement{};
  double expansion_rate = 0.0;

  template <class Archive>
  void serialize(Archive& ar) {
    ar(particles, time, step, bump_velocity, bump_displacement, expansion_rate);
  }
};

// The contact memory, by ids, and the engine's counters.
template <class State, class Statistics>
struct PortableContacts {
  using Pair = typename ContactStore<State>::KeptPair;  // by ids, the list's particle first
  using WallContact = typename ContactStore<State>::KeptWall;  // by the particle's id
  std::vector<Pair> pairs;         // touching pairs
  std::vector<WallContact> walls;  // touching particle-wall contacts
  Statistics stats{};              // contacts begun summed over ranks
  long rebuilds_since_sort = 0;

  template <class Archive>
  void serialize(Archive& ar) {
    ar(pairs, walls, stats, rebuilds_since_sort);
  }
  // Rank 0 puts the ranks' shares together.
  void add(const PortableContacts& share) {
    pairs.insert(pairs.end(), share.pairs.begin(), share.pairs.end());
    walls.insert(walls.end(), share.walls.begin(), share.walls.end());
    stats.collisions += share.stats.collisions;
    stats.wall_collisions += share.stats.wall_collisions;
    stats.max_overlap_ratio = std::max(stats.max_overlap_ratio, share.stats.max_overlap_ratio);
  }
};

}  // namespace grainflow::dem
