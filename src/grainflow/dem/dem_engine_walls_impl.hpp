// The soft-sphere engine's wall contacts: each wall's list of the particles near it, and the force
// loop over that list with the wall's shape inlined. Included by dem_engine_impl.hpp only.
#pragma once

#include <algorithm>
#include <array>
#include <type_traits>
#include <variant>

#include "grainflow/dem/dem_engine.hpp"
#include "grainflow/dem/thread_slices.hpp"

namespace grainflow::dem {

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::build_wall_list(std::size_t w) {
  const ParticleStore& p = s_.particles;
  const DemWall& wall = s_.walls[w];
  auto& list = contacts_.walls[w];
  const double reach = wall_reach_[w];
  std::visit(
      [&](const auto& shape) {
        if constexpr (std::is_same_v<std::decay_t<decltype(shape)>, walls::MeshWall>) {
          build_mesh_list(w, shape);
        } else {
          list.offsets.assign(1, 0);
          list.particle.clear();
          for (int e = 0; e < shape.elements(); ++e) {
            for (std::size_t i = 0; i < p.size(); ++i)
              if (p.motion[i] == Motion::free && !p.ghost[i] &&
                  shape.contact(e, p.position[i]).gap < p.target_radius[i] + reach)
                list.particle.push_back(static_cast<std::uint32_t>(i));
            list.offsets.push_back(static_cast<std::uint32_t>(list.particle.size()));
          }
        }
      },
      wall.shape);
  list.state.assign(list.size(), State{});
  list.touching.assign(list.size(), 0);
  wall_build_[w] = {wall.shift, s_.time};
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::build_mesh_list(std::size_t w, const walls::MeshWall& mesh) {
  const ParticleStore& p = s_.particles;
  auto& list = contacts_.walls[w];
  const double reach = wall_reach_[w];
  std::vector<std::uint32_t> near;
  list.candidate_offsets.assign(1, 0);
  list.candidates.clear();
  list.candidate_facets.clear();  // remade by the next force evaluation
  // The tree is asked in the mesh's own frame; a particle beyond its box and the reach is skipped at once.
  const Vec3 lo = mesh.surface->lo(), hi = mesh.surface->hi();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] != Motion::free || p.ghost[i]) continue;
    const Vec3 x = mesh.to_mesh(p.position[i]);
    const double r = p.target_radius[i] + reach;
    if (x.x < lo.x - r || x.y < lo.y - r || x.z < lo.z - r || x.x > hi.x + r || x.y > hi.y + r || x.z > hi.z + r)
      continue;
    const std::size_t before = list.candidates.size();
    mesh.surface->near(x, r, list.candidates);
    if (list.candidates.size() == before) continue;
    near.push_back(static_cast<std::uint32_t>(i));
    list.candidate_offsets.push_back(static_cast<std::uint32_t>(list.candidates.size()));
  }
  const auto n = static_cast<std::uint32_t>(near.size());
  list.offsets.resize(walls::MeshSurface::kMaxContacts + 1);
  list.particle.clear();
  for (int slot = 0; slot < walls::MeshSurface::kMaxContacts; ++slot) {
    list.offsets[slot] = slot * n;
    list.particle.insert(list.particle.end(), near.begin(), near.end());
  }
  list.offsets.back() = walls::MeshSurface::kMaxContacts * n;
  list.contact.assign(list.particle.size(), {});
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::refresh_moved_walls() {
  for (std::size_t w = 0; w < s_.walls.size(); ++w) {
    const DemWall& wall = s_.walls[w];
    if (!wall_moves_[w]) continue;  // a still surface's list waits for the neighbour list's rebuild
    if (wall.surface_travel(wall_build_[w].shift, wall_build_[w].time, wall.shift, s_.time) <= 0.5 * s_.skin) continue;
    auto kept = contacts_.take_wall_touching(s_.particles.id, static_cast<int>(w));
    ContactStore<State>::sort_kept(kept);
    build_wall_list(w);
    contacts_.restore_wall(w, kept, s_.particles.id);
  }
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::wall_forces(double dt) {
  ForceLoopSums all;
  all.max_ratio = stats_.max_overlap_ratio;
  wall_force_.resize(s_.walls.size());
  wall_torque_.resize(s_.walls.size());
  for (std::size_t w = 0; w < s_.walls.size(); ++w) {
    const ForceLoopSums sums = std::visit(
        [&](const auto& shape) {
          return s_.walls[w].spins() ? wall_forces_on<true>(w, shape, dt) : wall_forces_on<false>(w, shape, dt);
        },
        s_.walls[w].shape);
    wall_force_[w] = sums.force;
    wall_torque_[w] = sums.torque;
    all += sums;
  }
  stats_.wall_contacts = all.contacts;
  stats_.wall_collisions += all.begun;
  stats_.max_overlap_ratio = all.max_ratio;
  energy_.wall_power += all.boundary_power;
  energy_.growth_power += all.growth_power;
}

template <class Law, bool Rolling>
template <bool Spins>
inline void DemEngine<Law, Rolling>::wall_contact_force(const DemWall& wall, std::size_t w, const Params& params,
                                                        std::uint32_t i, const walls::SurfaceContact& sc, State& state,
                                                        double dt, ForceLoopSums& local) {
  ParticleStore& p = s_.particles;
  const double ri = p.radius[i];
  const double growth_rate = s_.expansion_rate;  // read before the stores below, which might alias it
  const Vec3 point = p.position[i] - sc.gap * sc.normal;
  const Vec3 surface = Spins ? wall.surface_velocity(point) : wall.velocity;
  const ContactKinematics c = wall_kinematics(i, surface, sc.normal, sc.gap);
  const ContactForce f = Law::force(params, law_state(state), c, dt);
  const Vec3 total = f.normal * sc.normal + f.tangential;
  p.force[i] += total;
  p.torque[i] -= ri * cross(sc.normal, f.tangential);
  Vec3 couple;
  if constexpr (Rolling) {
    RollingKinematics k_roll = rolling_kinematics(rolling_.walls[w], i, kWall, c, f.normal);
    if constexpr (Spins) k_roll.relative_spin -= wall.angular_velocity;
    couple = RollingResistance::torque(rolling_.walls[w], state.rolling, k_roll, dt);
    p.torque[i] += couple;
  }
  local.boundary_power += dot(total, surface);
  local.force += total;
  local.torque -= cross(point - wall.origin, total) + couple;  // the reaction, on the wall
  if (growth_rate > 0.0 && ri < p.target_radius[i]) local.growth_power += f.normal * growth_rate;
  local.max_ratio = std::max(local.max_ratio, c.overlap / (2.0 * ri));
  ++local.contacts;
}

template <class Law, bool Rolling>
template <bool Spins, class Shape>
ForceLoopSums DemEngine<Law, Rolling>::wall_forces_on(std::size_t w, const Shape& shape, double dt) {
  if constexpr (std::is_same_v<Shape, walls::MeshWall>) {
    return mesh_forces_on<Spins>(w, shape, dt);
  } else {
    const ParticleStore& p = s_.particles;
    const DemWall& wall = s_.walls[w];
    const Params& params = wall_params_[w];
    auto& list = contacts_.walls[w];
    ForceLoopSums wall_sums;
    // Element by element: a particle appears once in an element's list, so the threads' slices of it
    // never write to the same particle.
    for (std::size_t e = 0; e < list.elements(); ++e) {
      const std::uint32_t first = list.offsets[e];
      const int element = static_cast<int>(e);
      wall_sums += reduce_slices(threads_, list.offsets[e + 1] - first, ForceLoopSums{},
                                 [&](int, std::size_t begin, std::size_t end, ForceLoopSums& sum) {
                                   ForceLoopSums local;  // in registers, stored once at the slice's end
                                   for (std::size_t k = first + begin; k < first + end; ++k) {
                                     const std::uint32_t i = list.particle[k];
                                     const walls::SurfaceContact sc = shape.contact(element, p.position[i]);
                                     if (!wall_in_contact(sc.gap, p.radius[i], list.touching[k], params)) {
                                       list.touching[k] = 0;
                                       continue;
                                     }
                                     if (!list.touching[k]) {
                                       list.touching[k] = 1;
                                       list.state[k] = State{};
                                       ++local.begun;
                                     }
                                     wall_contact_force<Spins>(wall, w, params, i, sc, list.state[k], dt, local);
                                   }
                                   sum = local;
                                 });
    }
    return wall_sums;
  }
}

template <class Law, bool Rolling>
template <bool Spins>
ForceLoopSums DemEngine<Law, Rolling>::mesh_forces_on(std::size_t w, const walls::MeshWall& mesh, double dt) {
  constexpr int kSlots = walls::MeshSurface::kMaxContacts;
  const ParticleStore& p = s_.particles;
  const DemWall& wall = s_.walls[w];
  const Params& params = wall_params_[w];
  auto& list = contacts_.walls[w];
  const std::size_t n = list.elements() == 0 ? 0 : list.offsets[1];
  if (list.candidate_facets.size() != list.candidates.size()) {
    list.candidate_facets.clear();
    for (std::uint32_t f : list.candidates) list.candidate_facets.push_back(mesh.surface->facets()[f]);
  }
  // Particle by particle (its slots together): each appears once in a slot's block.
  return reduce_slices(threads_, n, ForceLoopSums{}, [&](int, std::size_t begin, std::size_t end, ForceLoopSums& sum) {
    ForceLoopSums local;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t i = list.particle[k];
      std::array<walls::SurfaceContact, kSlots> found;
      const std::uint32_t from = list.candidate_offsets[k];
      const int count =
          mesh.contacts(p.position[i], p.radius[i] + s_.cohesion_reach, list.candidate_facets.data() + from,
                        list.candidate_offsets[k + 1] - from, found.data());
      // Each contact continues the touching slot whose last normal it follows most closely (a
      // step turns a normal by far less than 60 degrees), or starts in a slot no contact continues.
      std::array<int, kSlots> slot;
      unsigned claimed = 0;
      for (int c = 0; c < count; ++c) {
        slot[c] = -1;
        double best = 0.5;
        for (int s = 0; s < kSlots; ++s) {
          const std::size_t q = list.offsets[s] + k;
          if (!list.touching[q] || (claimed >> s & 1u)) continue;
          const double along = dot(found[c].normal, list.contact[q].normal);
          if (along > best) best = along, slot[c] = s;
        }
        if (slot[c] >= 0) claimed |= 1u << slot[c];
      }
      for (int c = 0; c < count; ++c) {
        if (slot[c] >= 0) continue;
        int s = 0;
        while (claimed >> s & 1u) ++s;
        claimed |= 1u << s;
        slot[c] = s;
        list.touching[list.offsets[s] + k] = 0;  // a new contact: whatever the slot held has ended
      }
      for (int s = 0; s < kSlots; ++s)
        if (!(claimed >> s & 1u)) list.touching[list.offsets[s] + k] = 0;
      for (int c = 0; c < count; ++c) {
        const std::size_t q = list.offsets[slot[c]] + k;
        if (!wall_in_contact(found[c].gap, p.radius[i], list.touching[q], params)) {
          list.touching[q] = 0;
          continue;
        }
        if (!list.touching[q]) {
          list.touching[q] = 1;
          list.state[q] = State{};
          ++local.begun;
        }
        list.contact[q] = found[c];
        wall_contact_force<Spins>(wall, w, params, i, found[c], list.state[q], dt, local);
      }
    }
    sum = local;
  });
}

}  // namespace grainflow::dem
