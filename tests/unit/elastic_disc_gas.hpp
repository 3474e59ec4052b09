// An elastic hard-disc gas in equilibrium, sampled as an event-driven run's trajectory.h5 would hold
// it: 100 perfectly rough elastic discs (restitution 1, tangential restitution +1, so spin and
// translation exchange energy and share it equally, and no energy is lost) of radius R = 1 and
// unit mass at packing fraction 0.3 in a fully periodic square, no gravity. Started on a square
// lattice at T = 1 without spin, relaxed for t = 50 (Enskog: ~2.4 collisions per disc per unit
// time at nu = 0.3, so ~120 collisions each, far past equipartition), then sampled every 0.5
// (about one collision per disc between samples).
#pragma once

#include <cmath>
#include <string>

#include "grainflow/analysis/state_samples.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/edmd/edmd_engine.hpp"
#include "elastic_gas_case.hpp"

namespace grainflow::test {

constexpr int kGasDiscs = 100;
constexpr double kGasFraction = 0.3;

inline double gas_box_length() { return 10.0 * std::sqrt(M_PI / kGasFraction); }  // 10 x 10 lattice sites

inline analysis::StateSamples elastic_disc_gas_samples(int samples, double interval = 0.5, double relax = 50.0) {
  const double length = gas_box_length();
  const std::string text = elastic_gas_case({2, 10, kGasFraction, 2.0, 1.0, false, 5});
  edmd::EdmdEngine<2> e(edmd::build_edmd_state(load_case_from_string(text, "elastic_disc_gas.toml")));
  const auto& p = e.state().particles;
  analysis::StateSamples s;
  s.dimension = 2;
  s.particles = p.size();
  s.radius.assign(p.size(), 1.0);
  s.inertia_factor = 1.0 / (p.inv_inertia[0] * p.mass[0]);  // R = 1
  s.period_y = length;
  s.strip_count = static_cast<int>(std::lround(length / 2.0));  // about one diameter thick
  s.position.resize(samples * p.size() * 3);
  s.velocity.resize(s.position.size());
  s.angular_velocity.resize(s.position.size());
  for (int t = 0; t < samples; ++t) {
    e.advance_to(relax + t * interval);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Vec3 x = e.state().box.unwrapped(p.position[i], p.image[i]);
      const std::size_t k = p.id[i];  // columns by id: the engine re-sorts its store
      for (int a = 0; a < 3; ++a) {
        s.position[(t * p.size() + k) * 3 + a] = x[a];
        s.velocity[(t * p.size() + k) * 3 + a] = p.velocity[i][a];
        s.angular_velocity[(t * p.size() + k) * 3 + a] = p.angular_velocity[i][a];
      }
    }
    s.wall_lo.push_back(0.0);
    s.wall_hi.push_back(length);
    s.strip_lo.push_back(0.0);
    s.strip_hi.push_back(length);
    s.box_width.push_back(length);
  }
  s.samples = static_cast<std::size_t>(samples);
  return s;
}

}  // namespace grainflow::test
