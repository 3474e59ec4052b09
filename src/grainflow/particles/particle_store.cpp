#include "grainflow/particles/particle_store.hpp"

namespace grainflow {
namespace {

template <class T>
void apply(std::vector<T>& values, const std::vector<std::uint32_t>& order) {
  std::vector<T> sorted(order.size());
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
  ghost.resize(n, 0);
}

ParticleStore::Record ParticleStore::record(std::size_t i) const {
  return Record{position[i],
                velocity[i],
                angular_velocity[i],
                force[i],
                torque[i],
                radius[i],
                target_radius[i],
                inv_mass[i],
                inv_inertia[i],
                mass[i],
                image[i],
                species[i],
                id[i],
                motion[i],
                wall[i],
                ghost[i]};
}

void ParticleStore::push_back(const Record& r) {
  position.push_back(r.position);
  velocity.push_back(r.velocity);
  angular_velocity.push_back(r.angular_velocity);
  force.push_back(r.force);
  torque.push_back(r.torque);
  radius.push_back(r.radius);
  target_radius.push_back(r.target_radius);
  inv_mass.push_back(r.inv_mass);
  inv_inertia.push_back(r.inv_inertia);
  mass.push_back(r.mass);
  species.push_back(r.species);
  id.push_back(r.id);
  motion.push_back(r.motion);
  wall.push_back(r.wall);
  image.push_back(r.image);
  ghost.push_back(r.ghost);
}

void ParticleStore::permute(const std::vector<std::uint32_t>& order) {
  const bool has_ghost = ghost.size() == position.size();  // a store filled field by field (tests) may lack it
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
  if (has_ghost) apply(ghost, order);
  else ghost.assign(order.size(), 0);
}

}  // namespace grainflow
