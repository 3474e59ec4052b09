// The floor a vibrated bed rests on (the wall on the low face along gravity) and the driven face's
// motion, as the sampled outputs record them beside each sample.
#pragma once

#include <cmath>
#include <numbers>

#include "grainflow/config/case_config.hpp"
#include "grainflow/core/face_wall.hpp"

namespace grainflow::observe {

struct FloorMotion {
  double position = 0.0, velocity = 0.0;  // m, m/s along the axis; zero without a drive
};

// The driven wall's position and normal velocity now (zero without a drive).
inline FloorMotion floor_motion(const FaceWalls& walls, const CaseConfig& c) {
  FloorMotion m;
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (c.drive.enabled && walls[w].face == c.drive.face) m = {walls[w].position, walls[w].velocity[walls[w].axis]};
  return m;
}

// Position of the floor along `axis` now: its wall if it has one, else domain.lo.
inline double floor_position(const FaceWalls& walls, const CaseConfig& c, int axis) {
  const int w = walls.on_face(2 * axis);
  return w >= 0 ? walls[static_cast<std::size_t>(w)].position : c.domain.lo[axis];
}

// Phase of the floor's velocity cosine, omega (t - start) + phase, in [0, 2 pi); -1 without a
// drive along `axis` or before it starts.
inline double floor_phase(const CaseConfig& c, int axis, double time) {
  if (!c.drive.enabled || c.drive.face != 2 * axis || !(c.drive.frequency[axis] > 0.0) || time < c.drive.start)
    return -1.0;
  const double phase = 2.0 * M_PI * c.drive.frequency[axis] * (time - c.drive.start) + c.drive.phase[axis];
  return phase - 2.0 * M_PI * std::floor(phase / (2.0 * M_PI));
}

}  // namespace grainflow::observe
