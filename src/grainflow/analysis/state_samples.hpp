// Instantaneous states of an event-driven run, as stored in its trajectory.h5 (the "tape" of
// Campbell 1982 section 3.4): per sample the followed particles' positions, velocities and angular
// velocities, the y walls, the strips' bounds and the periodic width. Flow along x, gradient
// along y; in 3D z is periodic as well.
#pragma once

#include <cstddef>
#include <vector>

namespace grainflow::analysis {

struct StateSamples {
  int dimension = 2;
  std::size_t samples = 0, particles = 0;
  std::vector<double> position, velocity, angular_velocity;  // [samples][particles][3]; m, m/s, rad/s
  std::vector<double> radius;                                // [particles], m
  std::vector<double> wall_lo, wall_hi;                      // [samples], m: the y walls (box bounds where none)
  std::vector<double> strip_lo, strip_hi;                    // [samples], m: the strips' span along y
  std::vector<double> box_width;                             // [samples], m: the periodic length along x
  int strip_count = 1;
  double inertia_factor = 0.5;  // I / (m R^2): beta = inertia_factor R^2 turns spin into kinetic energy
  double period_y = 0.0;        // m, > 0 when y is periodic (no walls)
  double box_depth = 1.0;       // m, the box's length along z (3D)
  double z_lo = 0.0;            // m, where it starts
  bool periodic_z = true;       // 3D: z periodic (else bounded by walls at z_lo, z_lo + box_depth)

  const double* at(const std::vector<double>& field, std::size_t sample, std::size_t particle) const {
    return &field[(sample * particles + particle) * 3];
  }
  double mean_radius() const {
    double sum = 0.0;
    for (double r : radius) sum += r;
    return radius.empty() ? 0.0 : sum / static_cast<double>(radius.size());
  }
};

}  // namespace grainflow::analysis
