// The TC model (Luding & McNamara): a particle that collided less than a contact duration ago
// collides elastically and smoothly, as if it were still in contact. Inelastic collapse (ever
// more collisions, ever closer in time, in a cluster losing its relative motion) then cannot stop
// the clock. A contact duration of 0 turns the model off.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "grainflow/edmd/collision_rules.hpp"
#include "grainflow/edmd/free_flight.hpp"

namespace grainflow::edmd {

class TcModel {
 public:
  template <class Archive>
  void serialize(Archive& ar) {
    ar(last_collision_);
  }

  // `particles` that have never collided; `contact_duration` in s.
  void reset(std::size_t particles, double contact_duration) {
    last_collision_.assign(particles, -kNever);
    contact_duration_ = contact_duration;
  }

  // Whether a collision of i at `now` is a TC collision (elastic and smooth).
  bool recent(std::uint32_t i, double now) const { return now - last_collision_[i] < contact_duration_; }
  void note_collision(std::uint32_t i, double now) { last_collision_[i] = now; }
  double last_collision(std::size_t i) const { return last_collision_[i]; }  // s, -inf before the first
  const double* last_collision_address(std::uint32_t i) const { return &last_collision_[i]; }  // for prefetching

  const RestitutionLaw& elastic() const { return elastic_; }  // e = 1: no dissipation at all

 private:
  std::vector<double> last_collision_;  // s
  double contact_duration_ = 0.0;       // s
  RestitutionLaw elastic_;
};

}  // namespace grainflow::edmd
