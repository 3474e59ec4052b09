// The case text of one glass sphere (d = 2 mm, 2500 kg/m^3, read from `file`) on the ylo wall of a
// 2 cm box, x and z periodic, y open above, under gravity g tilted by `theta` (radians) down +x;
// `contact` holds the [contact] table's lines, `wall` the [walls.ylo] table's (none when empty).
// For the soft-sphere tests of a sphere rolling or sliding on a plane; `dimension` 2 makes it a
// disc in the x-y plane of the sphere's mass (its density per area 2500 kg/m^3 x 2/3 d), so that
// the contacts' stiffness and transients are the sphere's.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace grainflow::test {

inline std::string dem_incline_case(double g, double theta, const std::string& file, const std::string& contact,
                                    const std::string& wall = "", int dimension = 3) {
  char gravity[128];
  std::snprintf(gravity, sizeof gravity, "[%.17g, %.17g, 0.0]", g * std::sin(theta), -g * std::cos(theta));
  char density[64];
  std::snprintf(density, sizeof density, "%.17g", dimension == 2 ? 2500.0 * 2.0 / 3.0 * 0.002 : 2500.0);
  return "[engine]\ndimension = " + std::to_string(dimension) + R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.02, 0.02]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = )" +
         std::string(gravity) + R"(
[[species]]
name = "glass"
diameter = 0.002
density = )" +
         std::string(density) + R"(
[particles]
init = "file"
file = ")" +
         file + R"("
[contact]
)" + contact +
         (wall.empty() ? "" : "[walls.ylo]\n" + wall) + R"(
[run]
duration = 1.0
)";
}

}  // namespace grainflow::test
