// Strips across a shear flow (Campbell 1982, Fig. 2.11): `count` equal slabs between two planes
// normal to `axis` — the chute bottom and a fixed height, or a Couette cell's two walls, which move
// with the pressure servo (then call follow() before each use). A particle counts in each strip with
// the exact share of its area (discs) or volume (spheres) lying there; a collision's branch vector
// counts with the share of its length lying there (the stress carried across by the collision).
// Along a periodic axis (Lees-Edwards) the strips span exactly one period and a particle straddling
// the seam counts in the strips at both ends (set_period); the share beyond the seam is its image,
// which moves with the image row's velocity (Lees-Edwards: the boundaries' velocity jump).
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <vector>

#include "grainflow/analysis/partial_volume.hpp"
#include "grainflow/core/vec3.hpp"

namespace grainflow::observe {

class StripGrid {
 public:
  // `cross_section`: the strip's extent along the other axes, m (2D: the periodic width) or m^2.
  StripGrid(int dimension, int axis, double lo, double hi, int count, double cross_section)
      : dimension_(dimension), axis_(axis), count_(std::max(1, count)) {
    follow(lo, hi, cross_section);
  }

  // Moves the bounds (a Couette cell's walls at this instant); the strip count stays.
  void follow(double lo, double hi, double cross_section) {
    lo_ = lo;
    hi_ = hi;
    cross_section_ = cross_section;
    thickness_ = (hi - lo) / count_;
  }

  // The box's period along the axis, when the strips span it exactly; 0: not periodic.
  // `image_velocity`: how fast the image one period above moves relative to the particle (the
  // Lees-Edwards velocity jump, shear rate x period along the flow; zero in a plain periodic box).
  void set_period(double period, const Vec3& image_velocity = {}) {
    period_ = period;
    image_velocity_ = image_velocity;
  }
  double period() const { return period_; }
  const Vec3& image_velocity() const { return image_velocity_; }

  int dimension() const { return dimension_; }
  int axis() const { return axis_; }
  int count() const { return count_; }
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  double thickness() const { return thickness_; }
  double cross_section() const { return cross_section_; }
  double strip_lo(int k) const { return lo_ + k * thickness_; }
  double centre(int k) const { return lo_ + (k + 0.5) * thickness_; }
  // m^2 (2D) or m^3 (3D): the strip's area or volume.
  double measure() const { return thickness_ * cross_section_; }
  // The strip holding coordinate y, or -1 outside [lo, hi).
  int strip_of(double y) const {
    if (!(y >= lo_ && y < hi_)) return -1;
    return std::min(count_ - 1, static_cast<int>((y - lo_) / thickness_));
  }

  // visit(strip, part, fraction[, velocity_shift]): the particle's area (2D) or volume (3D) in each
  // strip it overlaps, that part as a fraction of the whole particle, and (when visit takes it) what
  // to add to the particle's velocity there: zero, or across the seam the image row's velocity.
  template <class Visit>
  void for_each_overlap(double centre, double radius, Visit&& visit) const {
    const double whole = dimension_ == 2 ? M_PI * radius * radius : 4.0 / 3.0 * M_PI * radius * radius * radius;
    overlap_at(centre, radius, whole, Vec3{}, visit);
    if (period_ > 0.0) {  // the part beyond the seam is the image counted at the other end
      if (centre - radius < lo_) overlap_at(centre + period_, radius, whole, image_velocity_, visit);
      if (centre + radius > hi_) overlap_at(centre - period_, radius, whole, -image_velocity_, visit);
    }
  }

  // visit(strip, fraction): the share of the segment from y0 to y1 (along the axis) in each strip;
  // a segment normal to the axis (y0 == y1) counts whole in its strip.
  template <class Visit>
  void for_each_segment_part(double y0, double y1, Visit&& visit) const {
    const double a = std::min(y0, y1), b = std::max(y0, y1);
    if (b == a) {
      if (const int k = strip_of(a); k >= 0) visit(k, 1.0);
      return;
    }
    const int first = std::max(0, static_cast<int>(std::floor((a - lo_) / thickness_)));
    const int last = std::min(count_ - 1, static_cast<int>(std::floor((b - lo_) / thickness_)));
    for (int k = first; k <= last; ++k) {
      const double inside = std::min(b, strip_lo(k) + thickness_) - std::max(a, strip_lo(k));
      if (inside > 0.0) visit(k, inside / (b - a));
    }
  }

 private:
  template <class Visit>
  void overlap_at(double centre, double radius, double whole, const Vec3& shift, Visit& visit) const {
    const int first = std::max(0, static_cast<int>(std::floor((centre - radius - lo_) / thickness_)));
    const int last = std::min(count_ - 1, static_cast<int>(std::floor((centre + radius - lo_) / thickness_)));
    for (int k = first; k <= last; ++k) {
      const double part = particle_slab_measure(dimension_, radius, centre, strip_lo(k), strip_lo(k) + thickness_);
      if (!(part > 0.0)) continue;
      if constexpr (std::is_invocable_v<Visit&, int, double, double, const Vec3&>) visit(k, part, part / whole, shift);
      else visit(k, part, part / whole);
    }
  }

  int dimension_, axis_, count_;
  double lo_ = 0.0, hi_ = 0.0, thickness_ = 0.0, cross_section_ = 0.0, period_ = 0.0;
  Vec3 image_velocity_;
};

}  // namespace grainflow::observe
