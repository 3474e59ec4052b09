// The soft-sphere engine's members for a restart on another rank count: its share of the state by
// particle ids (portable_state.hpp), and that state taken back. Part of dem_engine_impl.hpp, which
// includes it: compiled in each law's .cpp with the rest of the engine.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "grainflow/dem/dem_engine.hpp"

namespace grainflow::dem {

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::portable_share(PortableParticles& particles, Portable& contacts) const {
  const ParticleStore& p = s_.particles;
  particles.time = s_.time;
  particles.step = s_.step;
  particles.bump_velocity = s_.bump_velocity;
  particles.bump_displacement = s_.bump_displacement;
  particles.expansion_rate = s_.expansion_rate;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.ghost[i]) continue;
    particles.particles.push_back(p.record(i));
    for (std::uint32_t k = pairs_.offsets[i]; k < pairs_.offsets[i + 1]; ++k)
      if (contacts_.pair_touching[k]) {
        const std::uint32_t j = pairs_.partner[k];
        contacts.pairs.push_back(
            {p.id[i], p.id[j],
             ContactStore<State>::image_key(pairs_.shift[k], p.image[i], p.image[j], s_.box.shear_turns),
             contacts_.pair_state[k]});
      }
  }
  for (const auto& kept : contacts_.take_wall_touching(p.id))  // the lists hold owned particles only
    contacts.walls.push_back(kept);
  contacts.stats = stats_;
  contacts.rebuilds_since_sort = rebuilds_since_sort_;
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::restore_portable(const PortableParticles& particles, const Portable& contacts,
                                               bool totals_here) {
  ParticleStore& p = s_.particles;
  contacts_.restore(contacts.pairs, pairs_, p.id, p.image, s_.box.shear_turns);
  std::vector<std::int64_t> index(particles.particles.size(), -1);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.id[i] < index.size()) index[p.id[i]] = static_cast<std::int64_t>(i);
  // The lists the constructor built from the restored particles take their states.
  std::vector<typename ContactStore<State>::KeptWall> kept(contacts.walls);
  ContactStore<State>::sort_kept(kept);
  for (std::size_t w = 0; w < contacts_.walls.size(); ++w) contacts_.restore_wall(w, kept, p.id);
  for (const auto& r : particles.particles) {
    const std::int64_t i = r.id < index.size() ? index[r.id] : -1;
    if (i < 0) continue;
    p.force[i] = r.force;
    p.torque[i] = r.torque;
  }
  const ContactStatistics now = stats_;  // the contacts touching now, counted at construction
  stats_ = contacts.stats;
  stats_.contacts = now.contacts;
  stats_.wall_contacts = now.wall_contacts;
  if (!totals_here) stats_.collisions = stats_.wall_collisions = 0;
  rebuilds_since_sort_ = contacts.rebuilds_since_sort;
}

}  // namespace grainflow::dem
