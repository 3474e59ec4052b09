// The soft-sphere engine on several MPI ranks: each rank integrates the particles in its box of
// the grid (dem/domain_decomposition.hpp) and holds copies ("ghosts") of the other ranks' particles
// within reach of it, refreshed from their owners every step, so that every pair with an owned
// particle is evaluated exactly as on one rank. Messages go to the neighbouring ranks only (those
// whose boxes lie within reach), point to point. A pair across a boundary is evaluated on both ranks,
// in the same orientation (lower id first) from the same numbers, so both keep the same contact
// history bit for bit; only the sums of forces differ in order, by round-off.
//
// At a neighbour-list rebuild a particle that left the box goes to its new owner with its touching
// wall contacts' states and the states of its touching pairs, which only its owner is sure to have
// followed from the contact's start (a copy may have arrived mid-contact).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "grainflow/dem/contact_store.hpp"
#include "grainflow/dem/domain_decomposition.hpp"
#include "grainflow/parallel/communicator.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::dem {

namespace bytes {
template <class T>
void put(std::vector<std::uint8_t>& out, const T& value) {
  static_assert(std::is_trivially_copyable_v<T>);
  const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
  out.insert(out.end(), p, p + sizeof(T));
}
template <class T>
T take(const std::vector<std::uint8_t>& in, std::size_t& cursor) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (in.size() - cursor < sizeof(T)) throw std::runtime_error("domain exchange: a message ended early");
  T value;
  std::memcpy(&value, in.data() + cursor, sizeof(T));
  cursor += sizeof(T);
  return value;
}
}  // namespace bytes

// What an engine needs to run as one of several ranks.
struct EngineDomain {
  const parallel::Communicator* comm = nullptr;
  DomainDecomposition grid;
};

template <class State>
class DomainExchange {
 public:
  using KeptPair = typename ContactStore<State>::KeptPair;

  DomainExchange(const parallel::Communicator& comm, DomainDecomposition grid)
      : comm_(comm), grid_(std::move(grid)), neighbours_(grid_.neighbours(comm.rank())) {}

  const DomainDecomposition& grid() const { return grid_; }
  const std::vector<int>& neighbours() const { return neighbours_; }
  long long migrated() const { return migrated_; }  // particles this rank sent to another owner
  long long rebalances() const { return rebalances_; }
  long long ghosts() const {  // copies this rank holds now
    long long n = 0;
    for (const auto& ids : receive_ids_) n += static_cast<long long>(ids.size());
    return n;
  }
  bool any(bool local) const { return comm_.any(local); }
  void sum_in_place(double* values, std::size_t count) const { comm_.sum_in_place(values, count); }

  template <class Archive>  // checkpoints: this rank's cuts, counters and ghost bookkeeping
  void serialize(Archive& ar) {
    ar(grid_, neighbours_, migrated_, rebuilds_, rebalances_, send_ids_, receive_ids_, send_index_, receive_index_);
  }

  // The start: every rank built the same whole initial state; each keeps the particles in its slab.
  void keep_owned(ParticleStore& p) const {
    std::vector<std::uint32_t> mine;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (grid_.owner(p.position[i]) == comm_.rank()) mine.push_back(static_cast<std::uint32_t>(i));
    p.permute(mine);
  }

  // At a rebuild, after `kept` and `kept_walls` took the touching pairs' and wall contacts' states:
  // emigrants leave with their states, immigrants arrive with theirs (appended to `kept`, so they
  // win over a copy's; to `kept_walls`), ghosts are renewed.
  using KeptWall = typename ContactStore<State>::KeptWall;
  void redistribute(ParticleStore& p, std::vector<KeptPair>& kept, std::vector<KeptWall>& kept_walls) {
    const int me = comm_.rank(), ranks = comm_.size();
    const bool rebalanced = ++rebuilds_ % kRebalanceEvery == 0;
    if (rebalanced) rebalance(p);
    std::vector<std::uint32_t> stay;
    std::vector<std::pair<std::uint32_t, int>> leaving;  // (id, new owner), sorted by id
    std::vector<std::vector<std::uint8_t>> out(ranks);
    std::vector<std::uint32_t> count(ranks, 0);
    bool far = false;  // a particle moving to a rank beyond the neighbours (after cuts moved)
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.ghost[i]) continue;  // copies are dropped and sent afresh below
      const int r = grid_.owner(p.position[i]);
      if (r == me) {
        stay.push_back(static_cast<std::uint32_t>(i));
        continue;
      }
      far = far || !std::binary_search(neighbours_.begin(), neighbours_.end(), r);
      leaving.emplace_back(p.id[i], r);
      ++count[r];
      ++migrated_;
    }
    // Message: particle count and records, then pair count and pair states, then wall contacts.
    for (int r = 0; r < ranks; ++r) bytes::put(out[r], count[r]);
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.ghost[i]) continue;
      const int r = grid_.owner(p.position[i]);
      if (r == me) continue;
      bytes::put(out[r], p.record(i));
    }
    std::sort(leaving.begin(), leaving.end());
    auto destination = [&](std::uint32_t id) {
      const auto it = std::lower_bound(leaving.begin(), leaving.end(), std::make_pair(id, -1));
      return it != leaving.end() && it->first == id ? it->second : -1;
    };
    std::vector<std::vector<KeptPair>> pairs_out(ranks);
    for (const KeptPair& k : kept) {
      const int ra = destination(k.a), rb = destination(k.b);
      if (ra >= 0) pairs_out[ra].push_back(k);
      if (rb >= 0 && rb != ra) pairs_out[rb].push_back(k);
    }
    std::vector<std::vector<KeptWall>> walls_out(ranks);
    for (const KeptWall& k : kept_walls)
      if (const int r = destination(k.id); r >= 0) walls_out[r].push_back(k);
    for (int r = 0; r < ranks; ++r) {
      bytes::put(out[r], static_cast<std::uint64_t>(pairs_out[r].size()));
      for (const KeptPair& k : pairs_out[r]) bytes::put(out[r], k);
      bytes::put(out[r], static_cast<std::uint64_t>(walls_out[r].size()));
      for (const KeptWall& k : walls_out[r]) bytes::put(out[r], k);
    }
    out[me].clear();
    p.permute(stay);
    // Between rebalances a particle moves less than half a skin, so it stays within reach of its
    // old box and its new owner is a neighbour; after one (or if not) every rank talks to every rank.
    const bool everyone = comm_.any(rebalanced || far);
    const auto in = everyone ? comm_.exchange(out) : comm_.exchange_with(neighbours_, out);
    for (int r = 0; r < ranks; ++r) {
      if (r == me || in[r].empty()) continue;
      std::size_t cursor = 0;
      const auto arriving = bytes::take<std::uint32_t>(in[r], cursor);
      for (std::uint32_t k = 0; k < arriving; ++k) {
        ParticleStore::Record rec = bytes::take<ParticleStore::Record>(in[r], cursor);
        rec.ghost = 0;
        p.push_back(rec);
      }
      const auto states = bytes::take<std::uint64_t>(in[r], cursor);
      for (std::uint64_t k = 0; k < states; ++k) kept.push_back(bytes::take<KeptPair>(in[r], cursor));
      const auto wall_states = bytes::take<std::uint64_t>(in[r], cursor);
      for (std::uint64_t k = 0; k < wall_states; ++k) kept_walls.push_back(bytes::take<KeptWall>(in[r], cursor));
    }
    send_ghosts(p);
  }

  // After the rebuild's final ordering: where the ghosts sent and received sit now.
  void index(const ParticleStore& p) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> at(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) at[i] = {p.id[i], static_cast<std::uint32_t>(i)};
    std::sort(at.begin(), at.end());
    auto find = [&](std::uint32_t id) {
      const auto it = std::lower_bound(at.begin(), at.end(), std::make_pair(id, 0u));
      if (it == at.end() || it->first != id) throw std::logic_error("domain exchange: a ghost went missing");
      return it->second;
    };
    const int ranks = comm_.size();
    send_index_.assign(ranks, {});
    receive_index_.assign(ranks, {});
    for (int r = 0; r < ranks; ++r) {
      for (std::uint32_t id : send_ids_[r]) send_index_[r].push_back(find(id));
      for (std::uint32_t id : receive_ids_[r]) receive_index_[r].push_back(find(id));
    }
  }

  // Every step after the drift: the ghosts take their owners' current motion.
  void refresh(ParticleStore& p) const {
    const int ranks = comm_.size();
    std::vector<std::vector<std::uint8_t>> out(ranks);
    for (int r = 0; r < ranks; ++r) {
      out[r].reserve(send_index_[r].size() * sizeof(Moving));
      for (std::uint32_t i : send_index_[r])
        bytes::put(out[r], Moving{p.position[i], p.velocity[i], p.angular_velocity[i], p.radius[i], p.image[i]});
    }
    // Both sides know the counts since the last rebuild: no sizes sent ahead.
    std::vector<std::size_t> expected(ranks, 0);
    for (int r : neighbours_) expected[r] = receive_index_[r].size() * sizeof(Moving);
    const auto in = comm_.exchange_with(neighbours_, out, &expected);
    for (int r : neighbours_) {
      if (in[r].size() != receive_index_[r].size() * sizeof(Moving))
        throw std::logic_error("domain exchange: ghost counts disagree between ranks");
      std::size_t cursor = 0;
      for (std::uint32_t i : receive_index_[r]) {
        const Moving m = bytes::take<Moving>(in[r], cursor);
        p.position[i] = m.position;
        p.velocity[i] = m.velocity;
        p.angular_velocity[i] = m.angular_velocity;
        p.radius[i] = m.radius;
        p.image[i] = m.image;
      }
    }
  }

 private:
  struct Moving {
    Vec3 position, velocity, angular_velocity;
    double radius;
    std::array<std::int32_t, 3> image;
  };

  // Every kRebalanceEvery rebuilds the cuts move so that each slice of the grid holds as many
  // particles as the others again (a bed heaps, a chute's front moves); the particles then migrate
  // as usual, and the neighbours are found anew.
  static constexpr long kRebalanceEvery = 20;
  static constexpr int kBalanceBins = 4096;
  void rebalance(const ParticleStore& p) {
    std::vector<double> counts(3 * kBalanceBins, 0.0);  // the three axes' histograms, summed at once
    for (std::size_t i = 0; i < p.size(); ++i)
      if (!p.ghost[i])
        for (int a = 0; a < 3; ++a)
          if (grid_.cut(a)) counts[a * kBalanceBins + grid_.bin_of(p.position[i], a, kBalanceBins)] += 1.0;
    comm_.sum_in_place(counts.data(), counts.size());
    std::array<std::vector<double>, 3> by_axis;
    for (int a = 0; a < 3; ++a)
      by_axis[a].assign(counts.begin() + a * kBalanceBins, counts.begin() + (a + 1) * kBalanceBins);
    grid_.rebalance(by_axis);
    neighbours_ = grid_.neighbours(comm_.rank());
    ++rebalances_;
  }

  void send_ghosts(ParticleStore& p) {
    const int ranks = comm_.size();
    send_ids_.assign(ranks, {});
    receive_ids_.assign(ranks, {});
    std::vector<std::vector<std::uint8_t>> out(ranks);
    for (std::size_t i = 0; i < p.size(); ++i)
      for (int r : neighbours_) {
        if (grid_.distance_to(p.position[i], r) >= grid_.ghost_width) continue;
        bytes::put(out[r], p.record(i));
        send_ids_[r].push_back(p.id[i]);
      }
    const auto in = comm_.exchange_with(neighbours_, out);
    for (int r : neighbours_) {
      std::size_t cursor = 0;
      while (cursor < in[r].size()) {
        ParticleStore::Record rec = bytes::take<ParticleStore::Record>(in[r], cursor);
        rec.ghost = 1;
        p.push_back(rec);
        receive_ids_[r].push_back(rec.id);
      }
    }
  }

  const parallel::Communicator& comm_;
  DomainDecomposition grid_;
  std::vector<int> neighbours_;  // sorted
  long long migrated_ = 0, rebuilds_ = 0, rebalances_ = 0;
  std::vector<std::vector<std::uint32_t>> send_ids_, receive_ids_;      // by rank, in message order
  std::vector<std::vector<std::uint32_t>> send_index_, receive_index_;  // the same, as indices now
};

}  // namespace grainflow::dem
