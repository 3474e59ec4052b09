// The case text of one particle on an incline for event-driven unit tests: a unit-mass disc (2D) or
// sphere (3D) of radius 1, species "ball", read from `file`, above a floor wall at y = 0 with
// gravity g = 1 tilted by `alpha` (radians) down the x axis; the box is `width` along x (periodic),
// 10 high, 4 deep in 3D; particle and wall restitution 0.5, rolling_speed 0.05, the floor's wall
// condition as given (smooth, rough, no_slip).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace grainflow::test {

inline std::string incline_case(int dim, double width, double alpha, const std::string& file,
                                const std::string& condition, double duration) {
  const double density = dim == 2 ? 1.0 / M_PI : 3.0 / (4.0 * M_PI);  // unit mass at R = 1
  char text[2048];
  std::snprintf(text, sizeof text, R"([engine]
kind = "edmd"
dimension = %d
[domain]
lo = [0.0, 0.0, 0.0]
hi = [%.17g, 10.0, %g]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [%.17g, %.17g, 0.0]
[[species]]
name = "ball"
diameter = 2.0
density = %.17g
count = 0
[particles]
init = "file"
file = "%s"
[collision]
restitution = 0.5
rolling_speed = 0.05
[walls.ylo]
restitution = 0.5
condition = "%s"
[run]
duration = %.17g
)",
                dim, width, dim == 3 ? 4.0 : 1.0, std::sin(alpha), -std::cos(alpha), density, file.c_str(),
                condition.c_str(), duration);
  return text;
}

}  // namespace grainflow::test
