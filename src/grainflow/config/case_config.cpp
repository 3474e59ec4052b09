#include "grainflow/config/case_config.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/core/ball_measure.hpp"

namespace grainflow {

double SpeciesConfig::mass(int dimension) const { return ball_measure(dimension, 0.5 * diameter) * density; }

double trajectory_start(const CaseConfig& c) {
  return c.trajectory.start >= 0.0 ? c.trajectory.start : c.output.average_start;
}

double edmd_trajectory_interval(const CaseConfig& c) {
  if (c.trajectory.interval > 0.0) return c.trajectory.interval;
  return (c.run.duration - trajectory_start(c)) / static_cast<double>(c.trajectory.samples);
}

double CoarseGrainConfig::kernel_size(double reference_diameter) const {
  if (kernel == "lucy") return cutoff > 0.0 ? cutoff : std::sqrt(3.0) * reference_diameter;
  return width > 0.0 ? width : 0.5 * reference_diameter;
}

double lucy_standard_deviation(double cutoff, int dimension) {
  return cutoff * (dimension == 2 ? std::sqrt(5.0 / 56.0) : std::sqrt(1.0 / 12.0));
}

double CoarseGrainConfig::standard_deviation(double reference_diameter, int dimension) const {
  const double size = kernel_size(reference_diameter);
  return kernel == "lucy" ? lucy_standard_deviation(size, dimension) : size;
}

std::array<int, 3> CoarseGrainConfig::grid(const Vec3& box_length, double reference_diameter, int dimension) const {
  std::array<int, 3> out = cells;
  const double spacing = standard_deviation(reference_diameter, dimension);
  for (int a = 0; a < 3; ++a)
    if (out[a] <= 0) out[a] = std::max(1, static_cast<int>(std::ceil(box_length[a] / spacing - 1e-9)));
  if (dimension == 2 && cells[2] <= 0) out[2] = 1;
  return out;
}

}  // namespace grainflow
