#include "grainflow/observe/global_sample.hpp"

namespace grainflow::observe {

GlobalSample sample_global(const ParticleStore& p, int gravity_axis) {
  GlobalSample g;
  double mv2 = 0.0, height = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] != Motion::free) continue;
    const double m = p.mass[i];
    g.mass += m;
    g.momentum += m * p.velocity[i];
    mv2 += m * norm2(p.velocity[i]);
    g.rotational_energy += 0.5 * (1.0 / p.inv_inertia[i]) * norm2(p.angular_velocity[i]);
    height += m * p.position[i][gravity_axis];
  }
  g.kinetic_energy = 0.5 * mv2;
  if (g.mass > 0.0) {
    const Vec3 mean = g.momentum * (1.0 / g.mass);
    g.granular_temperature = (mv2 / g.mass - norm2(mean)) / 3.0;
    g.mass_center_height = height / g.mass;
  }
  return g;
}

}  // namespace grainflow::observe
