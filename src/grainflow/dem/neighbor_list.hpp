// Half neighbor lists in CSR form (offsets + partners + image shift codes): each pair closer than
// r_i + r_j + skin appears once, under the partner with the smaller id. Built from a cell grid, or
// by the all-pairs reference search used in tests. Pairs of two non-moving particles are skipped.
#pragma once

#include <cstdint>
#include <vector>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::dem {

struct NeighborPairs {
  std::vector<std::uint32_t> offsets;  // size n + 1; pairs of i are [offsets[i], offsets[i+1])
  std::vector<std::uint32_t> partner;  // index j
  std::vector<std::uint8_t> shift;     // image of j: x_j + shift_table[code]

  template <class Archive>
  void serialize(Archive& ar) {
    ar(offsets, partner, shift);
  }
  std::size_t pair_count() const { return partner.size(); }
};

// Cell grid over the box (clamped at non-periodic faces, so particles outside the box are still
// found). `cell_order` receives the particles sorted by cell, for spatial re-sorting.
class CellGrid {
 public:
  // Cells at least `cell_size` wide; wider where the box would otherwise need more than
  // max(32768, 4 x `particles`) of them.
  void setup(const PeriodicBox& box, double cell_size, std::size_t particles);
  void bin(const std::vector<Vec3>& position);
  const std::vector<std::uint32_t>& cell_order() const { return order_; }
  // `expected_pairs` (the last list's length, or 0) sizes the per-thread buffers up front, so that
  // their growth by doubling does not set the peak memory.
  void build_pairs(const ParticleStore& particles, const PeriodicBox& box, double skin, int threads,
                   NeighborPairs& out, std::size_t expected_pairs = 0) const;

 private:
  int cell_of(const Vec3& x) const;
  PeriodicBox box_;
  std::array<int, 3> cells_{1, 1, 1};
  Vec3 inv_size_;
  std::vector<std::uint32_t> start_;  // CSR over cells
  std::vector<std::uint32_t> order_;  // particle indices sorted by cell
  std::vector<int> cell_index_;       // cell of each particle
};

// Reference: every pair checked (O(n^2)); minimum image on periodic axes.
void build_pairs_all(const ParticleStore& particles, const PeriodicBox& box, double skin, NeighborPairs& out);

// True when the pair needs computing: at least one of the two moves.
inline bool pair_interacts(const ParticleStore& p, std::size_t i, std::size_t j) {
  return p.motion[i] == Motion::free || p.motion[j] == Motion::free;
}

}  // namespace grainflow::dem
