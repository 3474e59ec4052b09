// The case text of one glass sphere (d = 2 mm, 2500 kg/m^3, read from `file`) on the ylo wall of a
// 2 cm box, x and z periodic, y open above, under gravity g tilted by `theta` (radians) down +x;
// `contact` holds the [contact] table's lines, `wall` the [walls.ylo] table's (none when empty).
// For the soft-sphere tests of a sphere rolling or sliding on a plane.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace grainflow::test {

inline std::string dem_incline_case(double g, double theta, const std::string& file, const std::string& contact,
                                    const std::string& wall = "") {
  char gravity[128];
  std::snprintf(gravity, sizeof gravity, "[%.17g, %.17g, 0.0]", g * std::sin(theta), -g * std::cos(theta));
  return R"(
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.02, 0.02]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = )" + std::string(gravity) + R"(
[[species]]
name = "glass"
diameter = 0.002
density = 2500.0
[particles]
init = "file"
file = ")" + file + R"("
[contact]
)" + contact + (wall.empty() ? "" : "[walls.ylo]\n" + wall) + R"(
[run]
duration = 1.0
)";
}

}  // namespace grainflow::test
