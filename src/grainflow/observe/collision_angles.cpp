#include "grainflow/observe/collision_angles.hpp"

#include <algorithm>
#include <cmath>

namespace grainflow::observe {

double CollisionAngles::angle_of(const Vec3& line) {
  double theta = std::atan2(line.y, line.x);  // (-pi, pi]
  if (theta < 0.0) theta += M_PI;             // the opposite direction: same collision
  return theta >= M_PI ? 0.0 : theta;         // pi itself is the direction of 0
}

void CollisionAngles::add(const Vec3& line) {
  if (line.x == 0.0 && line.y == 0.0) {
    ++skipped_;
    return;
  }
  const int k = std::min(bins() - 1, static_cast<int>(angle_of(line) / bin_width()));
  ++counts_[k];
  ++total_;
}

double CollisionAngles::bin_width() const { return M_PI / bins(); }
double CollisionAngles::centre(int k) const { return (k + 0.5) * bin_width(); }
double CollisionAngles::density(int k) const {
  return total_ > 0 ? static_cast<double>(counts_[k]) / (static_cast<double>(total_) * bin_width()) : 0.0;
}

}  // namespace grainflow::observe
