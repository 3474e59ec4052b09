// Where an event-driven run's strips lie (Campbell 1982, Fig. 2.11): across the flow (along y,
// normal to the walls; the flow runs along x), `output.zone_thickness` thick (default one diameter
// of the first species). Between the two walls of a Couette cell: the count is fixed at the start
// from the gap and the strips stretch with the servo's walls. Over a chute bottom: from the ylo wall
// (or the domain's bottom) up to the domain's top, fixed.
#pragma once

#include <algorithm>
#include <cmath>

#include "grainflow/config/case_config.hpp"
#include "grainflow/analysis/strip_grid.hpp"
#include "grainflow/observe/observer.hpp"

namespace grainflow::observe {

class StripLayout {
 public:
  static constexpr int kAxis = 1;          // y: the velocity gradient (flow along x)
  static constexpr int kMaxStrips = 1000;  // block-averaged sums keep up to 512 copies of every strip

  StripLayout(const CaseConfig& c, const Frame& s) : dimension_(s.dimension), lees_edwards_rate_(c.lees_edwards_rate) {
    bottom_ = s.walls.with_role(WallRole::shear_bottom);
    top_ = s.walls.with_role(WallRole::shear_top);
    double thickness = c.output.zone_thickness > 0.0 ? c.output.zone_thickness : c.species.front().diameter;
    const auto [lo, hi] = bounds(s, s.time);
    const double extent = top_ >= 0 ? hi - lo : c.domain.hi[kAxis] - lo;
    // At most kMaxStrips: a domain millions of diameters tall gets thicker strips rather than
    // gigabytes of per-strip sums.
    count_ = static_cast<int>(std::clamp(std::round(extent / thickness), 1.0, static_cast<double>(kMaxStrips)));
    if (count_ == kMaxStrips) thickness = extent / count_;
    // Periodic along y (Lees-Edwards): the strips span the box exactly, so each end meets the other.
    if (top_ < 0) top_height_ = s.box->periodic[kAxis] ? s.box->hi[kAxis] : lo + count_ * thickness;
  }

  // The strips at time t (a Couette cell's walls and periodic width as they are then).
  StripGrid grid_at(const Frame& s, double t) const {
    const auto [lo, hi] = bounds(s, t);
    double cross_section = s.box->length(0);
    if (dimension_ == 3) cross_section *= s.box->length(2);
    StripGrid grid(dimension_, kAxis, lo, hi, count_, cross_section);
    if (top_ < 0 && bottom_ < 0 && s.box->periodic[kAxis])
      grid.set_period(s.box->length(kAxis), Vec3{lees_edwards_rate_ * s.box->length(kAxis), 0.0, 0.0});
    return grid;
  }

  bool between_walls() const { return top_ >= 0; }
  int count() const { return count_; }

 private:
  std::pair<double, double> bounds(const Frame& s, double t) const {
    const double lo = bottom_ >= 0 ? s.walls[bottom_].at(t) : s.box->lo[kAxis];
    const double hi = top_ >= 0 ? s.walls[top_].at(t) : top_height_;
    return {lo, hi};
  }

  int dimension_;
  double lees_edwards_rate_;    // 1/s: the image row above moves at this rate x the height
  int bottom_ = -1, top_ = -1;  // wall indices at ylo and yhi, -1 when none
  int count_ = 1;
  double top_height_ = 0.0;  // m, the top of the strips without a top wall
};

}  // namespace grainflow::observe
