#include "grainflow/observe/global_sample.hpp"

namespace grainflow::observe {

GlobalSample sample_global(const ParticleStore& p, int gravity_axis, int dimension, const RankReduce& ranks) {
  // mass, momentum (3), sum m v_a^2 (3), rotational energy, sum m height: summed over the ranks at
  // once.
  double sums[9] = {};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;
    const double m = p.mass[i];
    sums[0] += m;
    sums[1] += m * p.velocity[i].x;
    sums[2] += m * p.velocity[i].y;
    sums[3] += m * p.velocity[i].z;
    for (int a = 0; a < 3; ++a) sums[4 + a] += m * p.velocity[i][a] * p.velocity[i][a];
    sums[7] += 0.5 * (1.0 / p.inv_inertia[i]) * norm2(p.angular_velocity[i]);
    sums[8] += m * p.position[i][gravity_axis];
  }
  ranks.sum(sums, 9);
  const double twice_kinetic = sums[4] + sums[5] + sums[6];  // sum m |v|^2
  GlobalSample g;
  g.mass = sums[0];
  g.momentum = {sums[1], sums[2], sums[3]};
  g.kinetic_energy = 0.5 * twice_kinetic;
  g.rotational_energy = sums[7];
  if (g.mass > 0.0) {
    const Vec3 mean = g.momentum * (1.0 / g.mass);
    g.granular_temperature = (twice_kinetic / g.mass - norm2(mean)) / dimension;
    for (int a = 0; a < 3; ++a) g.component_temperature[a] = sums[4 + a] / g.mass - mean[a] * mean[a];
    g.mass_center_height = sums[8] / g.mass;
  }
  return g;
}

}  // namespace grainflow::observe
