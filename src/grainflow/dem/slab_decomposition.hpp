// How an MPI run of the soft-sphere engine splits its box: slabs along one axis, one per rank,
// their bounds placed at quantiles of the particles' coordinates so that each rank starts with
// the same number of particles (a bed or a chute is denser at the bottom, so equal widths would
// not balance it). The axis is the box's longest one across gravity: the flow direction of a chute,
// a horizontal one of a bed.
#pragma once

#include <vector>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/core/vec3.hpp"

namespace grainflow::dem {

struct SlabDecomposition {
  int axis = 0;
  std::vector<double> bounds;  // ranks + 1 values from box.lo[axis] to box.hi[axis]; rank r owns [bounds[r], bounds[r+1])
  bool periodic = false;
  double ghost_width = 0.0;    // m: a rank holds copies of the particles this close to its slab

  // Slabs for `ranks` ranks over `positions`; `gravity` picks the axis (the longest across it).
  static SlabDecomposition balanced(const std::vector<Vec3>& positions, const PeriodicBox& box, const Vec3& gravity,
                                    int ranks, double ghost_width);
  int ranks() const { return static_cast<int>(bounds.size()) - 1; }
  // Load balancing as the material moves: `counts` are the particles in equal bins along the axis
  // (every rank's, summed); the cuts move to where each rank gets the same number again, to the
  // resolution of a bin.
  void rebalance(const std::vector<double>& counts);
  int bin_of(const Vec3& x, int bins) const;
  // The rank owning a particle at `x` (coordinates outside the box go to the nearest end slab, or
  // wrap along a periodic axis).
  int owner(const Vec3& x) const;
  // Shortest distance along the axis from `x` to rank r's slab, through the periodic face too.
  double distance_to(const Vec3& x, int r) const;

  template <class Archive>  // checkpoints: the cuts move as the run goes
  void serialize(Archive& ar) {
    ar(axis, bounds, periodic, ghost_width);
  }
};

}  // namespace grainflow::dem
