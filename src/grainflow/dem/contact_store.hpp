// Contact memory (a law's State) for every neighbor pair and every particle-wall pair, carried
// across neighbor-list rebuilds and particle re-orderings by particle id.
#pragma once

#include <cstdint>
#include <vector>

#include "grainflow/dem/neighbor_list.hpp"

namespace grainflow::dem {

template <class State>
struct ContactStore {
  std::vector<State> pair_state;           // aligned with NeighborPairs::partner
  std::vector<std::uint8_t> pair_touching; // 1 while the pair overlaps
  std::vector<std::vector<State>> wall_state;            // [wall][particle]
  std::vector<std::vector<std::uint8_t>> wall_touching;  // [wall][particle]

  // Snapshot of the list the pair states refer to, by id, for the next transfer.
  std::vector<std::uint32_t> ids_at_build;       // index -> id when the list was built
  std::vector<std::uint32_t> index_at_build;     // id -> index when the list was built

  template <class Archive>
  void serialize(Archive& ar) {
    ar(pair_state, pair_touching, wall_state, wall_touching, ids_at_build, index_at_build);
  }

  void resize_walls(std::size_t walls, std::size_t particles) {
    wall_state.assign(walls, std::vector<State>(particles));
    wall_touching.assign(walls, std::vector<std::uint8_t>(particles, 0));
  }

  void permute_walls(const std::vector<std::uint32_t>& order) {
    for (std::size_t w = 0; w < wall_state.size(); ++w) {
      std::vector<State> s(order.size());
      std::vector<std::uint8_t> t(order.size());
      for (std::size_t i = 0; i < order.size(); ++i) {
        s[i] = wall_state[w][order[i]];
        t[i] = wall_touching[w][order[i]];
      }
      wall_state[w].swap(s);
      wall_touching[w].swap(t);
    }
  }

  // The states of the pairs touching now, by the list's particle index and the partner's id: all a
  // rebuild must carry (most listed pairs do not touch).
  struct Touching {
    std::vector<std::uint32_t> offsets;     // size n + 1, over the indices of the list they came from
    std::vector<std::uint32_t> partner_id;
    std::vector<State> state;
  };

  // Takes the touching pairs' states out of `old_list` (built when ids_at_build was recorded) and
  // frees the per-pair arrays, so that the next list is built without the old one's states beside it.
  Touching take_touching(const NeighborPairs& old_list) {
    Touching kept;
    const std::size_t n = old_list.offsets.empty() ? 0 : old_list.offsets.size() - 1;
    kept.offsets.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::uint32_t k = old_list.offsets[i]; k < old_list.offsets[i + 1]; ++k) {
        if (!pair_touching[k]) continue;
        kept.partner_id.push_back(ids_at_build[old_list.partner[k]]);
        kept.state.push_back(pair_state[k]);
      }
      kept.offsets[i + 1] = static_cast<std::uint32_t>(kept.state.size());
    }
    std::vector<State>().swap(pair_state);
    std::vector<std::uint8_t>().swap(pair_touching);
    return kept;
  }

  // Puts the kept states onto `new_list`, whose particle ids are `ids`.
  void restore(const Touching& kept, const NeighborPairs& new_list, const std::vector<std::uint32_t>& ids) {
    pair_state.assign(new_list.pair_count(), State{});
    pair_touching.assign(new_list.pair_count(), 0);
    for (std::size_t i = 0; i + 1 < new_list.offsets.size() && !kept.state.empty(); ++i) {
      const std::uint32_t old_i = index_at_build[ids[i]];
      const std::uint32_t old_begin = kept.offsets[old_i], old_end = kept.offsets[old_i + 1];
      if (old_begin == old_end) continue;
      for (std::uint32_t k = new_list.offsets[i]; k < new_list.offsets[i + 1]; ++k) {
        const std::uint32_t partner_id = ids[new_list.partner[k]];
        for (std::uint32_t q = old_begin; q < old_end; ++q) {
          if (kept.partner_id[q] == partner_id) {
            pair_state[k] = kept.state[q];
            pair_touching[k] = 1;
            break;
          }
        }
      }
    }
    record_ids(ids);
  }

  void record_ids(const std::vector<std::uint32_t>& ids) {
    ids_at_build = ids;
    std::uint32_t max_id = 0;
    for (std::uint32_t id : ids) max_id = std::max(max_id, id);
    index_at_build.assign(static_cast<std::size_t>(max_id) + 1, 0);
    for (std::size_t i = 0; i < ids.size(); ++i) index_at_build[ids[i]] = static_cast<std::uint32_t>(i);
  }
};

}  // namespace grainflow::dem
