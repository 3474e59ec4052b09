// One sphere's path against a wall, run under every contact law: each law's keys (particles' and
// walls'), a path sampled as (position, velocity, spin), and the largest differences between two
// paths. Shared by the tests that compare one wall with another that must move the sphere alike.
#pragma once

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow::test {

// Each law's keys, particles' and walls' (Hertzian laws need the glass's elastic constants).
inline std::string law_keys(std::string_view law) {
  if (law == "walton_braun") return "model = \"walton_braun\"\nk1 = 1.0e4\nrestitution = 0.8\nfriction = 0.3\n";
  if (law == "linear_dashpot") return "model = \"linear_dashpot\"\nkn = 1.0e4\ngamma_n = 0.05\nfriction = 0.3\n";
  if (law == "hertz_mindlin") return "model = \"hertz_mindlin\"\nrestitution = 0.8\nfriction = 0.3\n";
  return "model = \"jkr\"\nrestitution = 0.8\nsurface_energy = 0.002\nfriction = 0.3\n";
}
inline std::string wall_keys(std::string_view law) {
  if (law == "walton_braun") return "restitution = 0.6\nfriction = 0.4\n";
  if (law == "linear_dashpot") return "gamma_n = 0.08\nfriction = 0.4\n";
  return "restitution = 0.6\nyoungs_modulus = 2.0e8\nfriction = 0.4\n";
}
inline std::string species_keys(std::string_view law) {
  return law == "walton_braun" || law == "linear_dashpot" ? "" : "youngs_modulus = 1.0e8\npoisson_ratio = 0.25\n";
}

struct Motion3 {
  Vec3 x, v, w;
};

// The largest distances between two paths' positions, velocities and spins, sample by sample.
struct PathDifference {
  double position = 0.0, velocity = 0.0, spin = 0.0;
};
inline PathDifference largest_differences(const std::vector<Motion3>& a, const std::vector<Motion3>& b) {
  PathDifference d;
  for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) {
    d.position = std::max(d.position, norm(a[k].x - b[k].x));
    d.velocity = std::max(d.velocity, norm(a[k].v - b[k].v));
    d.spin = std::max(d.spin, norm(a[k].w - b[k].w));
  }
  return d;
}

}  // namespace grainflow::test
