// The measure of one particle: a disc's area in 2D, a sphere's volume in 3D. In 2D a density is a
// mass per unit area, so density times this measure is a particle's mass in either dimension.
#pragma once

#include <cmath>

namespace grainflow {

inline double ball_measure(int dimension, double radius) {
  return dimension == 2 ? M_PI * radius * radius : 4.0 / 3.0 * M_PI * radius * radius * radius;
}

// The moment of inertia's factor q in I = q m R^2: a uniform disc (1/2) or a solid sphere (2/5).
inline double ball_inertia_factor(int dimension) { return dimension == 2 ? 0.5 : 0.4; }

}  // namespace grainflow
