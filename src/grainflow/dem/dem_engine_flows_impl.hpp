// The soft-sphere engine's particles entering and leaving: outlets remove, insertions place.
// Applied at a neighbour-list rebuild, whose list then holds the new set (contact memory is kept
// by particle id). Included by dem_engine_impl.hpp only.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "grainflow/dem/dem_engine.hpp"
#include "grainflow/engine_api/energy_budget.hpp"

namespace grainflow::dem {

template <class Law, bool Rolling>
long DemEngine<Law, Rolling>::due(std::size_t k) const {
  const InsertionRegion& in = s_.insertions[k];
  if (s_.time < in.start) return 0;
  return in.count > 0 ? in.count : static_cast<long>(std::floor(in.rate * (s_.time - in.start)));
}

template <class Law, bool Rolling>
bool DemEngine<Law, Rolling>::exchange_due() const {
  if (!requested_in_.empty() || !requested_out_.empty()) return true;
  if (s_.insertions.empty() || s_.step - last_exchange_ < kExchangeSteps) return false;
  if (!waiting_.empty()) return true;
  for (std::size_t k = 0; k < s_.insertions.size(); ++k)
    if (due(k) > made_[k]) return true;
  return false;
}

// splitmix64 (Steele, Lea & Flood 2014): a counter is the whole state, so a checkpoint keeps it.
template <class Law, bool Rolling>
double DemEngine<Law, Rolling>::uniform() {
  std::uint64_t z = (draws_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-53;
}

// Removes the free particles whose centres lie in an outlet (those of an outlet that reinserts
// wait, at rest, for its insertion), makes the particles the insertions are due, and places those
// waiting. The energy budget's starting values take each one's energy off or on (kinetic and
// gravitational, along the bounded and the periodic axes, at the full step the budget counts it):
// the budget then follows the particles present, exactly, but for the elastic energy of contacts a
// removed particle leaves (outlets lie where grains fall free).
template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::exchange_particles() {
  ParticleStore& p = s_.particles;
  last_exchange_ = s_.step;
  removed_.clear();
  if (!s_.outlets.empty() || !requested_out_.empty()) {
    std::sort(requested_out_.begin(), requested_out_.end());
    std::vector<std::uint32_t> keep;
    keep.reserve(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
      int outlet = -1;
      if (p.counted(i))
        for (std::size_t o = 0; o < s_.outlets.size() && outlet < 0; ++o)
          if (s_.outlets[o].holds(p.position[i])) outlet = static_cast<int>(o);
      const bool requested = std::binary_search(requested_out_.begin(), requested_out_.end(), p.id[i]);
      if (outlet < 0 && !requested) {
        keep.push_back(static_cast<std::uint32_t>(i));
        continue;
      }
      if (p.moves(i)) count_out(i);
      if (outlet < 0) continue;
      ++outlet_counts_[outlet].removed;
      outlet_counts_[outlet].mass += p.mass[i];
      removed_.push_back({outlet, p.record(i)});
      if (s_.reinsert[outlet] >= 0) {
        ParticleStore::Record back = p.record(i);
        back.velocity = back.angular_velocity = back.force = back.torque = Vec3{};
        back.image = {0, 0, 0};
        waiting_.push_back({s_.reinsert[outlet], back});
      }
    }
    if (keep.size() != p.size()) p.permute(keep);
    requested_out_.clear();
  }
  for (const ParticleStore::Record& r : requested_in_) {
    p.push_back(r);
    s_.box.wrap(p.position.back(), p.image.back(), &p.velocity.back());
    count_in(p.size() - 1);
  }
  requested_in_.clear();
  for (std::size_t k = 0; k < s_.insertions.size(); ++k) {
    const InsertionRegion& in = s_.insertions[k];
    for (long n = due(k) - made_[k]; n > 0; --n) {
      ParticleStore::Record r{};
      r.velocity = in.velocity;
      r.radius = r.target_radius = in.radius;
      r.mass = in.mass;
      r.inv_mass = 1.0 / in.mass;
      r.inv_inertia = in.inv_inertia;
      r.species = in.species;
      r.id = next_id_++;
      r.motion = Motion::free;
      r.wall = -1;
      waiting_.push_back({static_cast<int>(k), r});
    }
    made_[k] = std::max(made_[k], due(k));
  }
  place_waiting();
}

// Each waiting particle gets up to 100 random tries in its region, its centre a radius inside the
// region where it is wide enough, clear of every wall (its surface at least a radius away: also
// on the inside of the wall an insertion names) and of every particle; one that finds no room
// waits for the next exchange.
template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::place_waiting() {
  if (waiting_.empty()) return;
  ParticleStore& p = s_.particles;
  double largest = 0.0;
  for (double r : p.target_radius) largest = std::max(largest, r);
  for (const Waiting& w : waiting_) largest = std::max(largest, w.particle.target_radius);
  const double cell = 2.0 * largest;
  const auto key = [&](const Vec3& x) {
    const auto c = [&](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(v / cell)) + (1 << 20)); };
    return (c(x.x) << 42) | (c(x.y) << 21) | c(x.z);
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> near;
  const auto in_any_region = [&](const Vec3& x) {
    for (const InsertionRegion& in : s_.insertions) {
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside = inside && x[a] >= in.lo[a] - cell && x[a] <= in.hi[a] + cell;
      if (inside) return true;
    }
    return false;
  };
  for (std::size_t i = 0; i < p.size(); ++i)
    if (in_any_region(p.position[i])) near[key(p.position[i])].push_back(static_cast<std::uint32_t>(i));
  const auto clear = [&](const Vec3& x, double r) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = near.find(key(x + Vec3{dx * cell, dy * cell, dz * cell}));
          if (it == near.end()) continue;
          for (std::uint32_t j : it->second)
            if (norm(s_.box.minimum_image(x, p.position[j])) < r + p.target_radius[j]) return false;
        }
    for (const DemWall& wall : s_.walls)
      if (walls::nearest_gap(wall.shape, x, r) < r) return false;
    return true;
  };
  std::vector<Waiting> still;
  for (Waiting& w : waiting_) {
    const InsertionRegion& in = s_.insertions[w.insertion];
    const double r = w.particle.target_radius;
    bool placed = false;
    for (int attempt = 0; attempt < 100 && !placed; ++attempt) {
      Vec3 x;
      for (int a = 0; a < 3; ++a) {
        const double margin = in.hi[a] - in.lo[a] > 2.0 * r ? r : 0.0;
        x[a] = in.lo[a] + margin + uniform() * (in.hi[a] - in.lo[a] - 2.0 * margin);
      }
      if (!clear(x, r)) continue;
      w.particle.position = x;
      w.particle.image = {0, 0, 0};
      p.push_back(w.particle);
      const std::size_t i = p.size() - 1;
      s_.box.wrap(p.position[i], p.image[i], &p.velocity[i]);
      near[key(p.position[i])].push_back(static_cast<std::uint32_t>(i));
      count_in(i);
      placed = true;
    }
    if (!placed) still.push_back(w);
  }
  waiting_.swap(still);
}

// A particle put in mid-step (at a rebuild): its energy at the end of this step, the first the
// budget counts; clear of every contact, only gravity acts in the step's second half kick.
template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::count_in(std::size_t i) {
  const ParticleStore& p = s_.particles;
  const Vec3 v = p.velocity[i] + (0.5 * s_.time_step) * s_.gravity;
  energy_.start_energy += 0.5 * p.mass[i] * norm2(v) + 0.5 * norm2(p.angular_velocity[i]) / p.inv_inertia[i] +
                          engine_api::bounded_potential(s_.box, s_.gravity, p.mass[i], p.position[i]);
  energy_.start_periodic_potential += periodic_potential_of(p.mass[i], s_.box.unwrapped(p.position[i], p.image[i]));
}

// A particle taken out mid-step: its energy at the last full step, which the budget counted.
template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::count_out(std::size_t i) {
  const ParticleStore& p = s_.particles;
  const double h = 0.5 * s_.time_step;
  const Vec3 v = p.velocity[i] - (h * p.inv_mass[i]) * p.force[i];
  const Vec3 w = p.angular_velocity[i] - (h * p.inv_inertia[i]) * p.torque[i];
  const Vec3 x = s_.box.unwrapped(p.position[i], p.image[i]) - s_.time_step * p.velocity[i];
  energy_.start_energy -= 0.5 * p.mass[i] * norm2(v) + 0.5 * norm2(w) / p.inv_inertia[i] +
                          engine_api::bounded_potential(s_.box, s_.gravity, p.mass[i], x);
  energy_.start_periodic_potential -= periodic_potential_of(p.mass[i], x);
}

template <class Law, bool Rolling>
std::vector<std::uint32_t> DemEngine<Law, Rolling>::add_particles(std::vector<ParticleStore::Record> particles) {
  if (domain_) throw std::invalid_argument("particles are added on one MPI rank only");
  const ParticleStore& p = s_.particles;
  const auto clash = [&](const Vec3& x, double r, const Vec3& y, double ry) {
    return norm(s_.box.minimum_image(x, y)) < r + ry;
  };
  for (std::size_t k = 0; k < particles.size(); ++k) {
    const ParticleStore::Record& r = particles[k];
    for (std::size_t i = 0; i < p.size(); ++i)
      if (clash(r.position, r.target_radius, p.position[i], p.target_radius[i]))
        throw std::invalid_argument("the new particle " + std::to_string(k) + " would overlap particle id " +
                                    std::to_string(p.id[i]));
    for (std::size_t j = 0; j < k; ++j)
      if (clash(r.position, r.target_radius, particles[j].position, particles[j].target_radius))
        throw std::invalid_argument("the new particles " + std::to_string(j) + " and " + std::to_string(k) + " overlap");
    for (const ParticleStore::Record& q : requested_in_)
      if (clash(r.position, r.target_radius, q.position, q.target_radius))
        throw std::invalid_argument("the new particle " + std::to_string(k) + " would overlap one added before");
    for (const DemWall& wall : s_.walls)
      if (walls::nearest_gap(wall.shape, r.position, r.target_radius) < r.target_radius)
        throw std::invalid_argument("the new particle " + std::to_string(k) + " would touch the wall '" + wall.name + "'");
  }
  std::vector<std::uint32_t> ids;
  for (ParticleStore::Record& r : particles) {
    r.id = next_id_++;
    ids.push_back(r.id);
    requested_in_.push_back(r);
  }
  return ids;
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::remove_particles(const std::vector<std::uint32_t>& ids) {
  if (domain_) throw std::invalid_argument("particles are removed on one MPI rank only");
  requested_out_.insert(requested_out_.end(), ids.begin(), ids.end());
}

}  // namespace grainflow::dem
