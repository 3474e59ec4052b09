#include "grainflow/analysis/savage_jeffrey.hpp"

#include <cmath>

namespace grainflow::analysis {

double savage_jeffrey_angle_density(double theta, double s) {
  return std::erfc(s * std::cos(theta) * std::sin(theta) / std::sqrt(2.0)) / M_PI;
}

double savage_jeffrey_shear_parameter(double radius, double shear_rate, double mean_square_normal_velocity) {
  return mean_square_normal_velocity > 0.0 ? 2.0 * radius * shear_rate / std::sqrt(mean_square_normal_velocity) : 0.0;
}

}  // namespace grainflow::analysis
