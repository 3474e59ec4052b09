// Contact memory (a law's State) for every neighbor pair and for the particles near each wall,
// carried across neighbor-list rebuilds and particle re-orderings by particle id.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "grainflow/dem/neighbor_list.hpp"
#include "grainflow/walls/mesh_surface.hpp"
#include "grainflow/walls/surface_contact.hpp"

namespace grainflow::dem {

// One wall's contact candidates: the particles within reach of each element of its surface when the
// list was built (elements one after another, particles in index order within each), so that a
// step's cost follows the particles near the wall, not the wall count times N.
// A mesh's list is different: its "elements" are contact slots (a sphere may press on a mesh at
// several places, MeshSurface::kMaxContacts), each slot's block holding the same particles; a slot
// keeps its history while its contact slides from triangle to triangle (matched by its normal).
template <class State>
struct WallContactList {
  std::vector<std::uint32_t> offsets{0};  // element e's entries are [offsets[e], offsets[e + 1])
  std::vector<std::uint32_t> particle;
  std::vector<State> state;
  std::vector<std::uint8_t> touching;  // 1 while the particle overlaps the element
  // A mesh's only: per particle of a slot's block, the triangles it may reach before the next
  // build ([candidate_offsets[k], candidate_offsets[k + 1]) of candidates); per entry its contact
  // at the last force evaluation.
  std::vector<std::uint32_t> candidate_offsets, candidates;
  std::vector<walls::SurfaceContact> contact;
  // Copies of the candidates' triangles in list order (a step streams through them); not saved:
  // remade from `candidates` whenever their counts differ.
  std::vector<walls::MeshFacet> candidate_facets;

  std::size_t size() const { return particle.size(); }
  std::size_t elements() const { return offsets.size() - 1; }
  template <class Archive>
  void serialize(Archive& ar) {
    ar(offsets, particle, state, touching, candidate_offsets, candidates, contact);
    candidate_facets.clear();
  }
};

template <class State>
struct ContactStore {
  std::vector<State> pair_state;            // aligned with NeighborPairs::partner
  std::vector<std::uint8_t> pair_touching;  // 1 while the pair overlaps
  std::vector<WallContactList<State>> walls;  // per wall: its candidates and their memory

  template <class Archive>
  void serialize(Archive& ar) {
    ar(pair_state, pair_touching, walls);
  }

  // A touching wall contact's state by particle id, wall and element: what a rebuild of the wall
  // lists carries over (and MPI sends along with a particle that changes ranks).
  struct KeptWall {
    std::uint32_t id, wall, element;
    State state;
    walls::SurfaceContact contact;  // a mesh's slot's last contact (matches it next step)
    auto key() const { return std::array<std::uint32_t, 3>{wall, id, element}; }
  };
  // The touching contacts of wall `wall` (every wall when -1), by id, sorted by key.
  std::vector<KeptWall> take_wall_touching(const std::vector<std::uint32_t>& ids, int wall = -1) const {
    std::vector<KeptWall> kept;
    for (std::size_t w = 0; w < walls.size(); ++w) {
      if (wall >= 0 && static_cast<int>(w) != wall) continue;
      const auto& list = walls[w];
      for (std::size_t e = 0; e < list.elements(); ++e)
        for (std::uint32_t k = list.offsets[e]; k < list.offsets[e + 1]; ++k)
          if (list.touching[k])
            kept.push_back({ids[list.particle[k]], static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(e),
                            list.state[k], list.contact.empty() ? walls::SurfaceContact{} : list.contact[k]});
    }
    return kept;
  }
  // Puts the kept states onto wall w's new list, whose particles have ids `ids`; `kept` sorted by key.
  // Where `kept` names a contact twice, the later entry wins (a migrating particle's, appended).
  void restore_wall(std::size_t w, const std::vector<KeptWall>& kept, const std::vector<std::uint32_t>& ids) {
    auto& list = walls[w];
    list.state.assign(list.size(), State{});
    list.touching.assign(list.size(), 0);
    if (kept.empty()) return;
    for (std::size_t e = 0; e < list.elements(); ++e)
      for (std::uint32_t k = list.offsets[e]; k < list.offsets[e + 1]; ++k) {
        const std::array<std::uint32_t, 3> key{static_cast<std::uint32_t>(w), ids[list.particle[k]],
                                               static_cast<std::uint32_t>(e)};
        auto it = std::upper_bound(kept.begin(), kept.end(), key,
                                   [](const auto& a, const KeptWall& b) { return a < b.key(); });
        if (it == kept.begin() || (it - 1)->key() != key) continue;
        list.state[k] = (it - 1)->state;
        list.touching[k] = 1;
        if (!list.contact.empty()) list.contact[k] = (it - 1)->contact;
      }
  }
  static void sort_kept(std::vector<KeptWall>& kept) {
    std::stable_sort(kept.begin(), kept.end(), [](const KeptWall& a, const KeptWall& b) { return a.key() < b.key(); });
  }

  // A touching pair's state by the two particles' ids, `a` the one whose list holds the pair: all a
  // rebuild must carry (most listed pairs do not touch). Ids, not indices, so that the particles
  // may be re-sorted, or leave and arrive (MPI ranks), between one list and the next.
  // `image`: which image of b, as box lengths between the unwrapped particles (the list's shift
  // plus a's and b's periodic crossings), which wrapping leaves alone: with a narrow periodic width
  // one pair touches at several images, each with its own state. Under Lees–Edwards shear an image
  // across the sliding rows also counts the widths taken off the offset (`shear_turns`,
  // periodic_box.hpp), so that the key stays the same when they are taken off.
  struct KeptPair {
    std::uint32_t a, b;
    std::array<std::int32_t, 3> image;
    State state;
  };
  using Images = std::vector<std::array<std::int32_t, 3>>;
  static std::array<std::int32_t, 3> image_key(std::uint8_t code, const std::array<std::int32_t, 3>& image_a,
                                               const std::array<std::int32_t, 3>& image_b,
                                               std::int32_t shear_turns = 0) {
    const auto s = PeriodicBox::shift_of(code);
    return {s[0] - s[1] * shear_turns + image_a[0] - image_b[0], s[1] + image_a[1] - image_b[1],
            s[2] + image_a[2] - image_b[2]};
  }

  // Takes the touching pairs' states out of `old_list`, whose particles have ids `ids` and periodic
  // crossings `images` (as when the list was built), and frees the per-pair arrays, so that the
  // next list is built without the old one's states beside it.
  std::vector<KeptPair> take_touching(const NeighborPairs& old_list, const std::vector<std::uint32_t>& ids,
                                      const Images& images, std::int32_t shear_turns = 0) {
    std::vector<KeptPair> kept;
    const std::size_t n = old_list.offsets.empty() ? 0 : old_list.offsets.size() - 1;
    for (std::size_t i = 0; i < n; ++i)
      for (std::uint32_t k = old_list.offsets[i]; k < old_list.offsets[i + 1]; ++k)
        if (pair_touching[k]) {
          const std::uint32_t j = old_list.partner[k];
          kept.push_back(
              {ids[i], ids[j], image_key(old_list.shift[k], images[i], images[j], shear_turns), pair_state[k]});
        }
    std::vector<State>().swap(pair_state);
    std::vector<std::uint8_t>().swap(pair_touching);
    return kept;
  }

  // Puts the kept states onto `new_list`, whose particles have ids `ids`. Where `kept` names a pair
  // twice, the later entry wins (a migrating particle's states, appended, replace a copy's).
  void restore(const std::vector<KeptPair>& kept, const NeighborPairs& new_list, const std::vector<std::uint32_t>& ids,
               const Images& images, std::int32_t shear_turns = 0) {
    pair_state.assign(new_list.pair_count(), State{});
    pair_touching.assign(new_list.pair_count(), 0);
    if (kept.empty()) return;
    // Grouped by the id of the list's particle (a counting sort keeps their order within a group).
    std::uint32_t largest = 0;
    for (const auto& k : kept) largest = std::max(largest, k.a);
    std::vector<std::uint32_t> start(static_cast<std::size_t>(largest) + 2, 0);
    for (const auto& k : kept) ++start[k.a + 1];
    for (std::size_t a = 0; a + 1 < start.size(); ++a) start[a + 1] += start[a];
    std::vector<std::uint32_t> order(kept.size()), fill(start.begin(), start.end() - 1);
    for (std::uint32_t q = 0; q < kept.size(); ++q) order[fill[kept[q].a]++] = q;
    for (std::size_t i = 0; i + 1 < new_list.offsets.size(); ++i) {
      if (ids[i] > largest) continue;
      const std::uint32_t begin = start[ids[i]], end = start[ids[i] + 1];
      if (begin == end) continue;
      for (std::uint32_t k = new_list.offsets[i]; k < new_list.offsets[i + 1]; ++k) {
        const std::uint32_t j = new_list.partner[k];
        const std::uint32_t partner_id = ids[j];
        for (std::uint32_t q = begin; q < end; ++q) {
          const KeptPair& entry = kept[order[q]];
          // The image key only for a kept pair with this partner (most listed pairs have none).
          if (entry.b != partner_id || entry.image != image_key(new_list.shift[k], images[i], images[j], shear_turns))
            continue;
          pair_state[k] = entry.state;  // no break: a later entry for the pair wins
          pair_touching[k] = 1;
        }
      }
    }
  }
};

}  // namespace grainflow::dem
