#include "grainflow/particles/particle_store.hpp"

namespace grainflow {
namespace {

template <class T>
void apply(std::vector<T>& values, const std::vector<std::uint32_t>& order) {
  std::vector<T> sorted(values.size());
  for (std::size_t i = 0; i < order.size(); ++i) sorted[i] = values[order[i]];
  values.swap(sorted);
}

}  // namespace

void ParticleStore::resize(std::size_t n) {
  position.resize(n);
  velocity.resize(n);
  angular_velocity.resize(n);
  force.resize(n);
  torque.resize(n);
  radius.resize(n);
  target_radius.resize(n);
  inv_mass.resize(n);
  inv_inertia.resize(n);
  mass.resize(n);
  species.resize(n);
  id.resize(n);
  motion.resize(n, Motion::free);
  wall.resize(n, -1);
  image.resize(n, {0, 0, 0});
}

void ParticleStore::permute(const std::vector<std::uint32_t>& order) {
  apply(position, order);
  apply(velocity, order);
  apply(angular_velocity, order);
  apply(force, order);
  apply(torque, order);
  apply(radius, order);
  apply(target_radius, order);
  apply(inv_mass, order);
  apply(inv_inertia, order);
  apply(mass, order);
  apply(species, order);
  apply(id, order);
  apply(motion, order);
  apply(wall, order);
  apply(image, order);
}

}  // namespace grainflow
