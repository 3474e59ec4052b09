// The distribution of collision angles (Campbell 1982 section 3.4.2, Fig. 3.31a): theta is the
// angle of the line of centres from the flow direction x, towards y, folded into [0, 180) degrees
// since a collision has no order (the line from j to i and from i to j give the same theta). In
// 3D the line of centres is projected on the x-y plane (the plane of the shear). 50 equal bins as
// Campbell's; the density is per radian and integrates to 1.
#pragma once

#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow::observe {

class CollisionAngles {
 public:
  explicit CollisionAngles(int bins = 50) : counts_(bins, 0) {}

  // theta of a line of centres, in [0, pi) radians.
  static double angle_of(const Vec3& line);
  void add(const Vec3& line_of_centres);

  int bins() const { return static_cast<int>(counts_.size()); }
  double bin_width() const;    // rad
  double centre(int k) const;  // rad
  long long count(int k) const { return counts_[k]; }
  long long total() const { return total_; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(counts_, total_, skipped_);
  }
  double density(int k) const;                    // 1/rad: count / (total x bin width); 0 with no collisions
  long long skipped() const { return skipped_; }  // 3D lines along z, which have no angle in x-y

 private:
  std::vector<long long> counts_;
  long long total_ = 0, skipped_ = 0;
};

}  // namespace grainflow::observe
