// Half neighbor lists in CSR form (offsets + partners + image shift codes): each pair closer than
// r_i + r_j + skin appears once, under the partner with the smaller id. Built from a cell grid, or
// by the all-pairs reference search used in tests. Pairs of two non-moving particles are skipped.
// A periodic width shorter than two cutoffs holds one cell: then every image of a partner within
// the cutoff is listed, each once (the same pair may appear with several shift codes), and so is a
// particle's own image (under a shift code above PeriodicBox::kNoShift, the other direction being
// the same contact).
#pragma once

#include <array>
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
  // A grid over part of the box only: an MPI rank's sub-domain widened by its ghost layer, so that
  // a rank's cells scale with its particles, not with the whole box. Along the axes in `cut` the
  // grid spans [lo, hi] and does not wrap; a particle there (a ghost from across a periodic face)
  // is binned at its periodic image inside [lo, hi], and its pairs carry that image in their
  // shift codes, so the forces see the same separations as on one rank.
  void setup_region(const PeriodicBox& box, const Vec3& lo, const Vec3& hi, const std::array<bool, 3>& cut,
                    double cell_size, std::size_t particles);
  void bin(const std::vector<Vec3>& position);
  const std::vector<std::uint32_t>& cell_order() const { return order_; }
  // `expected_pairs` (the last list's length, or 0) sizes the per-thread buffers up front, so that
  // their growth by doubling does not set the peak memory.
  void build_pairs(const ParticleStore& particles, const PeriodicBox& box, double skin, int threads, NeighborPairs& out,
                   std::size_t expected_pairs = 0) const;

 private:
  int cell_of(const Vec3& x) const;
  // `Framed`: particles sit at their images inside a cut region (MPI). `Wide`: more than one
  // neighbour cell each way along some axis, or Lees–Edwards rows; otherwise the 27 cells around
  // each, with the loop bounds known to the compiler.
  template <bool Framed, bool Wide>
  void search(const ParticleStore& p, const PeriodicBox& box, double skin, std::size_t begin, std::size_t end,
              std::vector<std::uint32_t>& partners, std::vector<std::uint8_t>& codes,
              std::vector<std::uint32_t>& counts) const;
  PeriodicBox box_;
  Vec3 lo_;                                        // the grid's origin (the box's, or the region's)
  std::array<bool, 3> wraps_{};                    // periodic and not cut: neighbour cells wrap around
  std::array<bool, 3> framed_{};                   // periodic and cut: particles binned at an image
  std::vector<std::array<std::int8_t, 3>> frame_;  // each particle's image along the framed axes
  std::array<int, 3> cells_{1, 1, 1};
  std::array<int, 3> reach_{1, 1, 1};  // neighbour cells searched each way: images along a one-cell axis
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
