// The case text of an elastic hard-particle gas for event-driven unit tests: n^dim equal particles
// of unit mass (discs in 2D, spheres in 3D) on a square / simple-cubic lattice whose spacing gives
// exactly the packing fraction asked for, Gaussian velocities at T = 1 with zero total momentum, no
// gravity, restitution 1. Periodic on every axis, or between smooth elastic walls at y = 0 and L.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

namespace grainflow::test {

struct ElasticGas {
  int dimension = 2;
  int per_side = 10;      // n: n^dim particles
  double fraction = 0.3;  // packing (area / volume) fraction
  double diameter = 1.0;
  double tangential = -1.0;  // tangential restitution: -1 smooth, +1 elastic rough
  bool walls = false;        // smooth elastic walls at ylo and yhi instead of a periodic y
  int seed = 5;
};

// Lattice spacing and box edge (n spacings) of the gas.
inline double gas_spacing(const ElasticGas& g) {
  const double r = 0.5 * g.diameter;
  const double particle = g.dimension == 3 ? 4.0 / 3.0 * M_PI * r * r * r : M_PI * r * r;
  return std::pow(particle / g.fraction, 1.0 / g.dimension);
}
inline double gas_length(const ElasticGas& g) { return g.per_side * gas_spacing(g); }

inline std::string elastic_gas_case(const ElasticGas& g) {
  const double r = 0.5 * g.diameter, length = gas_length(g);
  const double particle = g.dimension == 3 ? 4.0 / 3.0 * M_PI * r * r * r : M_PI * r * r;
  const int count = g.dimension == 3 ? g.per_side * g.per_side * g.per_side : g.per_side * g.per_side;
  char text[2048];
  std::snprintf(text, sizeof text, R"([engine]
kind = "edmd"
dimension = %d
[domain]
lo = [0.0, 0.0, 0.0]
hi = [%.17g, %.17g, %.17g]
boundary = { x = "periodic", y = "%s", z = "periodic" }
[gravity]
vector = [0.0, 0.0, 0.0]
[[species]]
name = "p"
diameter = %.17g
density = %.17g
count = %d
[particles]
init = "lattice"
lattice_spacing = %.17g
initial_temperature = 1.0
seed = %d
[collision]
restitution = 1.0
tangential_restitution = %g
%s
[run]
duration = 1.0
)",
                g.dimension, length, length, g.dimension == 3 ? length : 1.0, g.walls ? "wall" : "periodic", g.diameter,
                1.0 / particle, count, gas_spacing(g) / g.diameter * (1.0 - 1e-9) /* n sites fit despite rounding */,
                g.seed, g.tangential,
                g.walls ? "[walls.ylo]\nrestitution = 1.0\ncondition = \"smooth\"\n[walls.yhi]\nrestitution = "
                          "1.0\ncondition = \"smooth\""
                        : "");
  return text;
}

}  // namespace grainflow::test
