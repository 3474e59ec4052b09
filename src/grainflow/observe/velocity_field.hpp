// Mean velocity on a grid of cells in the plane of the gravity axis and one horizontal axis, each
// cell spanning the third axis (Lan 1994 Chapter 5, Fig. 5.1): a particle's velocity counts toward
// the cell holding its centre at the sampled instant, and a cell's mean is the plain average over
// those visits (Lan's "mean velocity in a small cell"). Kept long-term and per bin of the floor
// cycle (Figs. A5.1-A5.11). The average convection speed of Table 5.1 is the visit-weighted mean
// of the cells' mean speeds.
#pragma once

#include <vector>

#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

struct FieldCell {
  int column = 0, row = 0;                                    // along the horizontal and the vertical axis
  double horizontal = 0.0, vertical = 0.0;                    // m, cell centre
  long visits = 0;                                            // particle centres counted
  double velocity_horizontal = 0.0, velocity_vertical = 0.0;  // m/s, mean over visits
  double speed() const;                                       // m/s, magnitude of the mean
};

class VelocityField {
 public:
  // Cells of `cell` x `cell` over [h_lo, h_hi] x [v_lo, v_hi]; `bins` phase bins besides the
  // long-term field (0 = none).
  VelocityField(int horizontal_axis, int vertical_axis, double h_lo, double h_hi, double v_lo, double v_hi, double cell,
                int bins);
  // One sample; `bin` in [0, bins) or -1 for the long-term field only.
  void sample(const ParticleStore& particles, int bin);
  // MPI: each rank sampled its own particles; this sums the cells over the ranks (once, before
  // the field is read).
  void sum_over_ranks(const RankReduce& ranks);
  // A restart on another rank count: one rank keeps the summed cells, the others start from zero.
  void clear_sums();
  std::vector<FieldCell> cells(int bin = -1) const;  // -1: long-term
  // Visit-weighted mean of the cells' mean speeds (Table 5.1's average convection velocity).
  double convection_speed() const;
  // Lan's own average (Table 5.1): the plain mean of the cells' mean speeds, every cell counting
  // once, over the cells visited at least `min_visit_fraction` times as often as the mean visited
  // cell (0: every visited cell). A sparsely visited cell's mean speed is noisy and biased upward,
  // so the cut-off shows how much the plain mean depends on them.
  double cell_mean_convection_speed(double min_visit_fraction = 0.0) const;
  long samples() const { return samples_; }
  int bins() const { return bins_; }
  int columns() const { return columns_; }
  int rows() const { return rows_; }
  double cell() const { return cell_; }  // m

  template <class Archive>
  void serialize(Archive& ar) {
    ar(long_term_, by_bin_, samples_);
  }

 private:
  struct Sums {
    long visits = 0;
    double h = 0.0, v = 0.0;
  };
  int h_axis_, v_axis_;
  double h_lo_, v_lo_, cell_;
  int columns_, rows_, bins_;
  std::vector<Sums> long_term_;
  std::vector<std::vector<Sums>> by_bin_;
  long samples_ = 0;
};

}  // namespace grainflow::observe
