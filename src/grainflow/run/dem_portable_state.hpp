// The engine's part of a checkpoint's portable state (dem/portable_state.hpp): every rank's share
// gathered and put together on rank 0, and read back before and after the engine is built on
// another number of ranks.
#pragma once

#include <algorithm>
#include <string>

#include "grainflow/dem/dem_state.hpp"
#include "grainflow/dem/portable_state.hpp"
#include "grainflow/io/state_archive.hpp"
#include "grainflow/parallel/communicator.hpp"

namespace grainflow::run {

// Collective: writes the engine's state, gathered over the ranks, into `ar` (rank 0's archive holds
// it all; the others' are not kept).
template <class Engine>
void write_portable_engine(io::StateArchive& ar, const Engine& e, const parallel::Communicator& comm) {
  dem::PortableParticles particles;
  typename Engine::Portable contacts;
  e.portable_share(particles, contacts);
  if (comm.size() > 1) {
    io::StateArchive mine = io::StateArchive::for_writing();
    mine(particles, contacts);
    auto shares = comm.gather(mine.bytes());
    for (std::size_t r = 0; r < shares.size(); ++r) {  // rank 0 only: the others got none
      io::StateArchive in =
          io::StateArchive::for_reading(std::move(shares[r]), "rank " + std::to_string(r) + "'s share");
      dem::PortableParticles theirs;
      typename Engine::Portable their_contacts;
      in(theirs, their_contacts);
      if (r == 0) {
        particles = std::move(theirs);
        contacts = std::move(their_contacts);
      } else {
        particles.particles.insert(particles.particles.end(), theirs.particles.begin(), theirs.particles.end());
        contacts.add(their_contacts);
      }
    }
  }
  std::sort(particles.particles.begin(), particles.particles.end(),
            [](const ParticleStore::Record& a, const ParticleStore::Record& b) { return a.id < b.id; });
  ar(particles, contacts);
}

// Before the engine is built: the checkpoint's particles and clock put into the case's initial
// state (the sub-domains are then placed on them).
inline void read_portable_particles(io::StateArchive& ar, dem::PortableParticles& particles, dem::DemState& initial) {
  ar(particles);
  initial.particles = ParticleStore{};
  for (ParticleStore::Record r : particles.particles) {
    r.ghost = 0;
    initial.particles.push_back(r);
  }
  initial.time = particles.time;
  initial.step = particles.step;
  initial.bump_velocity = particles.bump_velocity;
  initial.bump_displacement = particles.bump_displacement;
  initial.expansion_rate = particles.expansion_rate;
}

// After: the contact memory, the last forces and the counters (`totals_here`: on one rank).
template <class Engine>
void read_portable_contacts(io::StateArchive& ar, Engine& e, const dem::PortableParticles& particles,
                            bool totals_here) {
  typename Engine::Portable contacts;
  ar(contacts);
  e.restore_portable(particles, contacts, totals_here);
}

}  // namespace grainflow::run
