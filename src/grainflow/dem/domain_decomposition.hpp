// How an MPI run of the soft-sphere engine splits its box: a grid of px x py x pz sub-domains, one
// per rank, each a box. The grid's shape comes from the rank count and the shape of the material
// (the particles' extent): of all px py pz = P, the one with the least cut area, hence the fewest
// ghosts, among those whose sub-domains are at least two ghost layers thick and, where that allows,
// that leave gravity's axis uncut (the material settles along it). A bed is therefore cut into
// slabs or columns, a gravity-free cube in all three axes, a tall narrow silo across its height.
// Along each cut axis the cuts sit at quantiles of the particles' coordinates, so that a bed denser
// at the bottom or a chute's front still gives each rank its share, and they move with the
// material (`rebalance`).
#pragma once

#include <array>
#include <vector>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/core/vec3.hpp"

namespace grainflow::dem {

struct DomainDecomposition {
  std::array<int, 3> shape{1, 1, 1};  // sub-domains along x, y, z; rank = cx + px (cy + py cz)
  // Per axis, shape[a] + 1 values from box.lo[a] to box.hi[a]; coordinate c owns [bounds[c], bounds[c+1]).
  std::array<std::vector<double>, 3> bounds;
  std::array<bool, 3> periodic{};
  double ghost_width = 0.0;  // m: a rank holds copies of the particles this close to its box

  // The grid for `ranks` ranks over `positions` in `box`; `gravity`'s axis is left uncut where
  // the others allow.
  static DomainDecomposition balanced(const std::vector<Vec3>& positions, const PeriodicBox& box, const Vec3& gravity,
                                      int ranks, double ghost_width);
  // The shape alone: of px py pz = ranks, with sub-domains at least `min_thickness` thick where
  // cut, and `down` (the gravity axis, -1 for none) uncut where possible, the least cut area over
  // `extent` (the material's size per axis); ties go to fewer cut axes.
  static std::array<int, 3> choose_shape(int ranks, const std::array<double, 3>& extent,
                                         const std::array<bool, 3>& periodic, double min_thickness, int down);

  int ranks() const { return shape[0] * shape[1] * shape[2]; }
  bool cut(int axis) const { return shape[axis] > 1; }
  std::array<int, 3> coordinates(int rank) const;
  int rank_at(const std::array<int, 3>& c) const { return c[0] + shape[0] * (c[1] + shape[1] * c[2]); }
  // The rank owning a particle at `x` (coordinates outside the box go to the nearest end
  // sub-domain, or wrap along a periodic axis).
  int owner(const Vec3& x) const;
  // Shortest distance from `x` to rank r's box, through periodic faces; the end sub-domains reach
  // on beyond a non-periodic box face.
  double distance_to(const Vec3& x, int r) const;
  // The ranks whose boxes lie within ghost_width of rank r's (through periodic faces), r excluded:
  // all a rank exchanges ghosts and migrants with between rebalances.
  std::vector<int> neighbours(int r) const;
  // Rank r's box: [lo, hi] along each axis (the box's own extent along uncut axes).
  Vec3 lower(int r) const;
  Vec3 upper(int r) const;

  // Load balancing as the material moves: `counts[a]` are the particles in equal bins along axis
  // a (every rank's, summed); each cut axis's cuts move to where each slice of the grid gets the
  // same number again, to the resolution of a bin.
  void rebalance(const std::array<std::vector<double>, 3>& counts);
  int bin_of(const Vec3& x, int axis, int bins) const;

  template <class Archive>  // checkpoints: the cuts move as the run goes
  void serialize(Archive& ar) {
    ar(shape, bounds, periodic, ghost_width);
  }

 private:
  double wrapped(double v, int axis) const;  // into [lo, hi) along a periodic axis
  int coordinate(double v, int axis) const;
  double axis_gap(double v, int axis, int c) const;  // distance along one axis to slice c
};

}  // namespace grainflow::dem
