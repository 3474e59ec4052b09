#include "grainflow/observe/global_sample.hpp"

namespace grainflow::observe {

GlobalSample sample_global(const ParticleStore& p, int gravity_axis, const RankReduce& ranks) {
  // mass, momentum (3), sum m v^2, rotational energy, sum m height, sum m v_a^2 (3): summed over the
  // ranks at once.
  double sums[10] = {};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;
    const double m = p.mass[i];
    sums[0] += m;
    sums[1] += m * p.velocity[i].x;
    sums[2] += m * p.velocity[i].y;
    sums[3] += m * p.velocity[i].z;
    sums[4] += m * norm2(p.velocity[i]);
    sums[5] += 0.5 * (1.0 / p.inv_inertia[i]) * norm2(p.angular_velocity[i]);
    sums[6] += m * p.position[i][gravity_axis];
    for (int a = 0; a < 3; ++a) sums[7 + a] += m * p.velocity[i][a] * p.velocity[i][a];
  }
  ranks.sum(sums, 10);
  GlobalSample g;
  g.mass = sums[0];
  g.momentum = {sums[1], sums[2], sums[3]};
  g.kinetic_energy = 0.5 * sums[4];
  g.rotational_energy = sums[5];
  if (g.mass > 0.0) {
    const Vec3 mean = g.momentum * (1.0 / g.mass);
    g.granular_temperature = (sums[4] / g.mass - norm2(mean)) / 3.0;
    for (int a = 0; a < 3; ++a) g.component_temperature[a] = sums[7 + a] / g.mass - mean[a] * mean[a];
    g.mass_center_height = sums[6] / g.mass;
  }
  return g;
}

}  // namespace grainflow::observe
