// The soft-sphere engine's member definitions. Only the file that instantiates the engine for a
// law includes this (each law's .cpp: `template class DemEngine<Law>;`), so that the time loop is
// compiled once per law, with the law inlined, and not again in every file that runs an engine.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

#include "grainflow/dem/dem_engine.hpp"
#include "grainflow/dem/dem_engine_portable_impl.hpp"
#include "grainflow/dem/dem_engine_flows_impl.hpp"
#include "grainflow/dem/dem_engine_walls_impl.hpp"
#include "grainflow/dem/thread_slices.hpp"

namespace grainflow::dem {

template <class Law, bool Rolling>
DemEngine<Law, Rolling>::DemEngine(DemState state, Params pair_params, std::vector<Params> wall_params, int threads,
                                   int sort_every, const EngineDomain* domain, RollingSetup rolling)
    : s_(std::move(state)),
      pair_params_(pair_params),
      wall_params_(std::move(wall_params)),
      threads_(std::max(1, threads)),
      sort_every_(sort_every),
      rolling_(std::move(rolling)) {
  if constexpr (Rolling) {
    if (rolling_.walls.size() != s_.walls.size()) throw std::invalid_argument("DemEngine: one RollingParams per wall");
    bump_rolling_.fill(rolling_.pair);
  }
  s_.particles.ghost.assign(s_.particles.size(), 0);
  contacts_.walls.assign(s_.walls.size(), {});
  outlet_counts_.assign(s_.outlets.size(), {});
  made_.assign(s_.insertions.size(), 0);
  for (std::uint32_t id : s_.particles.id) next_id_ = std::max(next_id_, id + 1);
  wall_build_.assign(s_.walls.size(), {});
  // A still surface's list holds while the particles move half a skin (the neighbour list's
  // rebuild); a moving one's is rebuilt when the surface has moved half a skin, by which time a
  // particle may have moved a whole skin since it was built.
  for (const DemWall& wall : s_.walls) {
    const bool moves = wall.motion.moves() || wall.turns || (s_.servo.config.enabled && wall.face >= 0);
    wall_moves_.push_back(moves);
    wall_reach_.push_back((moves ? 1.5 : 0.5) * s_.skin + s_.cohesion_reach);
  }
  bump_wall_.fill(-1);
  bump_owner_.fill(-1);
  bump_params_.fill(pair_params_);
  has_bumps_ = std::any_of(s_.particles.wall.begin(), s_.particles.wall.end(), [](auto face) { return face >= 0; });
  for (std::size_t w = 0; w < s_.walls.size(); ++w) {
    if (!s_.walls[w].bumpy) continue;
    bump_owner_[s_.walls[w].face] = static_cast<int>(w);
    bump_params_[s_.walls[w].face] = wall_params_[w];  // bumps carry their wall's e and mu
    if constexpr (Rolling) bump_rolling_[s_.walls[w].face] = rolling_.walls[w];
    if (s_.walls[w].motion.moves()) bump_wall_[s_.walls[w].face] = static_cast<int>(w);
  }
  double max_radius = 0.0;
  for (double r : s_.particles.target_radius) max_radius = std::max(max_radius, r);
  cell_size_ = 2.0 * max_radius + s_.skin + s_.cohesion_reach;
  grid_.setup(s_.box, cell_size_, s_.particles.size());
  if (domain != nullptr && domain->comm->size() > 1) {
    domain_ = std::make_unique<DomainExchange<State>>(*domain->comm, domain->grid);
    domain_->keep_owned(s_.particles);
    rank_ = domain->comm->rank();
  }
  for (auto& wall : s_.walls) wall.move_to(s_.time);
  restart_from_current_state();
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::restart_from_current_state() {
  const auto builds = stats_.rebuilds;  // a new start: its build is the first, as the constructor's was
  rebuild(true);
  if (builds > 0) stats_.rebuilds = builds;
  // The initial evaluation must not advance contact histories (no time has passed): dt = 0.
  compute_forces(0.0);
  servo_ = DemCouetteServo(s_);
  if (servo_.enabled()) {
    const auto inputs = servo_inputs();
    servo_.start_loads(inputs[0], inputs[1]);
  }
  energy_.contact_power = contact_power();
  energy_.start_elastic = elastic_energy();
  energy_.start_energy = engine_api::mechanical_energy(s_.particles, s_.box, s_.gravity) + energy_.start_elastic;
  energy_.start_periodic_potential = engine_api::periodic_potential(s_.particles, s_.box, s_.gravity);
}

template <class Law, bool Rolling>
engine_api::EnergyBudget DemEngine<Law, Rolling>::energy_budget() const {
  engine_api::EnergyBudget b;
  const double elastic = elastic_energy();
  b.gravity_work = energy_.start_periodic_potential - engine_api::periodic_potential(s_.particles, s_.box, s_.gravity);
  b.wall_work = energy_.wall_work;
  b.boundary_work = energy_.seam_contact_work + energy_.seam_crossing_work;
  b.growth_work = energy_.growth_work;
  b.change = engine_api::mechanical_energy(s_.particles, s_.box, s_.gravity) + elastic - energy_.start_energy;
  // on the contacts' relative motion
  const double relative_work = energy_.contact_work - energy_.wall_work - energy_.seam_contact_work;
  b.dissipated = energy_.growth_work - relative_work - (elastic - energy_.start_elastic);
  return b;
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::step() {
  ParticleStore& p = s_.particles;
  const double dt = s_.time_step;
  const std::size_t n = p.size();
  half_kick<false>();
  for_each_slice(threads_, n, [&](int, std::size_t begin, std::size_t end) {
    // Raw arrays: through the store the compiler would reload every array's address per particle.
    const Motion* motion = p.motion.data();
    const std::uint8_t* ghost = p.ghost.data();
    const Vec3* velocity = p.velocity.data();
    Vec3* position = p.position.data();
    const double step = dt;  // a copy: the captured reference would be reloaded after each store
    for (std::size_t i = begin; i < end; ++i)
      if (motion[i] == Motion::free && !ghost[i]) position[i] += step * velocity[i];
  });
  s_.time = (s_.step + 1) * dt;  // no accumulated round-off in the clock
  ++s_.step;
  if (s_.box.sheared()) s_.box.shear_offset = s_.box.shear_velocity * s_.time - s_.box.shear_turns * s_.box.length(0);
  move_walls();
  energy_.growth_work += dt * energy_.growth_power;  // this step's growth against the forces before it
  grow_radii();
  if (domain_) domain_->refresh(p);  // ghosts take their owners' new positions and velocities
  if (domain_ ? domain_->any(needs_rebuild()) : needs_rebuild() || exchange_due()) rebuild(false);
  else refresh_moved_walls();
  const double contact_before = energy_.contact_power, wall_before = energy_.wall_power,
               seam_before = energy_.seam_power;
  compute_forces(dt);
  energy_.contact_power = half_kick<true>();
  energy_.contact_work += 0.5 * dt * (contact_before + energy_.contact_power);
  energy_.wall_work += 0.5 * dt * (wall_before + energy_.wall_power);
  energy_.seam_contact_work += 0.5 * dt * (seam_before + energy_.seam_power);
  if (servo_.enabled()) servo_step(dt);
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::servo_step(double dt) {
  const auto inputs = servo_inputs();
  servo_.add_loads(dt, inputs[0], inputs[1]);
  const auto collisions = static_cast<long long>(inputs[2]);
  if (!servo_.due(s_, collisions)) {
    servo_.observe(s_);
    return;
  }
  const Vec3 bottom = s_.walls[servo_.bottom_wall()].velocity, top = s_.walls[servo_.top_wall()].velocity;
  servo_.update(s_, collisions);
  // The walls move at their new speeds from now: the next step's work starts from this power.
  energy_.wall_power += dot(wall_force_[servo_.bottom_wall()], s_.walls[servo_.bottom_wall()].velocity - bottom) +
                        dot(wall_force_[servo_.top_wall()], s_.walls[servo_.top_wall()].velocity - top);
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::compute_forces(double history_dt) {
  ParticleStore& p = s_.particles;
  const std::size_t n = p.size();
  // Gravity, and zero for the non-moving.
  const Vec3 gravity = s_.gravity;
  for_each_slice(threads_, n, [&](int, std::size_t begin, std::size_t end) {
    const Motion* motion = p.motion.data();  // raw arrays, as in the drift
    const double* mass = p.mass.data();
    Vec3 *force = p.force.data(), *torque = p.torque.data();
    const Vec3 g = gravity;
    for (std::size_t i = begin; i < end; ++i) {
      force[i] = motion[i] == Motion::free ? mass[i] * g : Vec3{};
      torque[i] = Vec3{};
    }
  });
  energy_.wall_power = energy_.growth_power = energy_.seam_power = 0.0;
  pair_forces(history_dt);
  wall_forces(history_dt);
}

template <class Law, bool Rolling>
std::vector<engine_api::Coordination> DemEngine<Law, Rolling>::coordination() const {
  std::vector<Coordination> c(s_.particles.size());
  for (std::size_t a = 0; a + 1 < pairs_.offsets.size(); ++a)
    for (std::uint32_t k = pairs_.offsets[a]; k < pairs_.offsets[a + 1]; ++k)
      if (contacts_.pair_touching[k]) {
        ++c[a].particles;
        ++c[pairs_.partner[k]].particles;
      }
  for (const auto& list : contacts_.walls)
    for (std::size_t k = 0; k < list.size(); ++k) c[list.particle[k]].walls += list.touching[k] != 0;
  return c;
}

template <class Law, bool Rolling>
template <bool Measure>
double DemEngine<Law, Rolling>::half_kick() {
  ParticleStore& p = s_.particles;
  const double half = 0.5 * s_.time_step;
  const std::size_t n = p.size();
  const Vec3 gravity = s_.gravity;
  return reduce_slices(threads_, n, 0.0, [&](int, std::size_t begin, std::size_t end, double& sum) {
    // Raw arrays and locals: the velocity stores would otherwise oblige the compiler to reload
    // gravity and to store the running power on every particle.
    const Motion* motion = p.motion.data();
    const std::uint8_t* ghost = p.ghost.data();
    const Vec3 *force = p.force.data(), *torque = p.torque.data();
    const double *inv_mass = p.inv_mass.data(), *inv_inertia = p.inv_inertia.data(), *mass = p.mass.data();
    Vec3 *velocity = p.velocity.data(), *angular_velocity = p.angular_velocity.data();
    const double h = half;  // copies inside the slice: the captured references would be reloaded
    const Vec3 g = gravity;
    double power = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      if (motion[i] != Motion::free || ghost[i]) continue;
      const Vec3 f = force[i], t = torque[i];
      const Vec3 v = velocity[i] + (h * inv_mass[i]) * f;
      const Vec3 w = angular_velocity[i] + (h * inv_inertia[i]) * t;
      velocity[i] = v;
      angular_velocity[i] = w;
      if constexpr (Measure) power += contact_power_of(f, t, mass[i], g, v, w);
    }
    sum = power;
  });
}

template <class Law, bool Rolling>
double DemEngine<Law, Rolling>::contact_power() const {
  const ParticleStore& p = s_.particles;
  double power = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.counted(i))
      power += contact_power_of(p.force[i], p.torque[i], p.mass[i], s_.gravity, p.velocity[i], p.angular_velocity[i]);
  return power;
}

template <class Law, bool Rolling>
double DemEngine<Law, Rolling>::elastic_energy() const {
  const ParticleStore& p = s_.particles;
  const auto shifts = s_.box.shift_table();
  double e = 0.0;
  for (std::size_t i = 0; i + 1 < pairs_.offsets.size(); ++i) {
    if (p.ghost[i]) continue;
    for (std::uint32_t k = pairs_.offsets[i]; k < pairs_.offsets[i + 1]; ++k) {
      if (!contacts_.pair_touching[k]) continue;
      const std::uint32_t j = pairs_.partner[k];
      const double overlap =
          p.radius[i] + p.radius[j] - norm(p.position[i] - (p.position[j] + shifts[pairs_.shift[k]]));
      const int bump_face = std::max(p.wall[i], p.wall[j]);
      const double effective_radius = p.radius[i] * p.radius[j] / (p.radius[i] + p.radius[j]);
      e += Law::elastic_energy(bump_face < 0 ? pair_params_ : bump_params_[bump_face],
                               law_state(contacts_.pair_state[k]), energy_overlap(overlap), effective_radius);
      if constexpr (Rolling)
        e += RollingResistance::elastic_energy(bump_face < 0 ? rolling_.pair : bump_rolling_[bump_face],
                                               contacts_.pair_state[k].rolling, effective_radius);
    }
  }
  for (std::size_t w = 0; w < s_.walls.size(); ++w) {
    const auto& list = contacts_.walls[w];
    std::visit(
        [&](const auto& shape) {
          for (std::size_t el = 0; el < list.elements(); ++el)
            for (std::uint32_t k = list.offsets[el]; k < list.offsets[el + 1]; ++k) {
              const std::uint32_t i = list.particle[k];
              if (!list.touching[k] || !p.counted(i)) continue;
              const double overlap = p.radius[i] - listed_contact(shape, list, el, k, p.position[i]).gap;
              e += Law::elastic_energy(wall_params_[w], law_state(list.state[k]), energy_overlap(overlap),
                                       p.radius[i]);
              if constexpr (Rolling)
                e += RollingResistance::elastic_energy(rolling_.walls[w], list.state[k].rolling, p.radius[i]);
            }
        },
        s_.walls[w].shape);
  }
  return e;
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::move_walls() {
  for (auto& wall : s_.walls) wall.move_to(s_.time);
  // Bumps ride on their wall: shift them by the wall's displacement since the last step.
  ParticleStore& p = s_.particles;
  bool any_bumps = false;
  std::array<Vec3, 6> delta{};
  for (int f = 0; f < 6; ++f) {
    if (bump_wall_[f] < 0) continue;
    const WallMotion& motion = s_.walls[bump_wall_[f]].motion;
    const Vec3 now = motion.displacement(s_.time);
    delta[f] = now - s_.bump_displacement[f];
    s_.bump_displacement[f] = now;
    s_.bump_velocity[f] = motion.velocity(s_.time);
    any_bumps = true;
  }
  if (!any_bumps) return;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] != Motion::wall_bump) continue;
    p.position[i] += delta[p.wall[i]];
    p.velocity[i] = s_.bump_velocity[p.wall[i]];
  }
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::grow_radii() {
  if (s_.expansion_rate <= 0.0) return;
  ParticleStore& p = s_.particles;
  bool growing = false;
  const double dr = s_.expansion_rate * s_.time_step;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.radius[i] < p.target_radius[i]) {
      p.radius[i] = std::min(p.target_radius[i], p.radius[i] + dr);
      growing = true;
    }
  }
  if (!growing) s_.expansion_rate = 0.0;
}

template <class Law, bool Rolling>
bool DemEngine<Law, Rolling>::needs_rebuild() const {
  const ParticleStore& p = s_.particles;
  // A pair's separation changes by at most both displacements plus, across a Lees–Edwards seam,
  // the rows' slide since the build: the list holds while that stays within the skin.
  const double slack = s_.skin - std::fabs(s_.box.shear_offset - offset_at_build_);
  if (!(slack > 0.0)) return true;
  const double limit = 0.25 * slack * slack;  // (slack / 2)^2
  const std::size_t n = p.size();
  const std::size_t moved =
      reduce_slices(threads_, n, std::size_t{0}, [&](int, std::size_t begin, std::size_t end, std::size_t& count) {
        const Vec3 *position = p.position.data(), *at_build = position_at_build_.data();
        std::size_t local = 0;  // in a register, not stored per particle through `count`
        for (std::size_t i = begin; i < end; ++i)
          local += !(norm2(position[i] - at_build[i]) <= limit);  // a NaN rebuilds, and is caught there
        count = local;
      });
  return moved != 0;
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::rebuild(bool first) {
  ParticleStore& p = s_.particles;
  std::optional<std::size_t> broken;
  for (std::size_t i = 0; i < p.size() && !broken; ++i)
    if (!p.ghost[i] && !fault_detail::finite(p.position[i])) broken = i;
  // MPI: every rank learns of a fault on any rank here, before the exchange below, so that all
  // stop at this step together (and write their outputs) instead of waiting on the faulty one.
  if (domain_ ? domain_->any(broken.has_value()) : broken.has_value())
    throw broken ? non_finite_state(s_, *broken) : NonFiniteState(kFaultOnAnotherRank);  // the run adds the cause
  // The touching pairs' states, by particle id and image, are set aside and the old list freed
  // before the new one is built, so that the peak memory holds one list, not two. Until here the
  // particles are in the old list's order and unwrapped as when it was built.
  std::vector<typename ContactStore<State>::KeptPair> kept;
  std::vector<typename ContactStore<State>::KeptWall> kept_walls;
  if (!first) {
    kept = contacts_.take_touching(pairs_, p.id, p.image, s_.box.shear_turns);
    kept_walls = contacts_.take_wall_touching(p.id);
    if (s_.exchanges || !requested_in_.empty() || !requested_out_.empty())
      exchange_particles();  // the kept states name particles by id: they follow
  }
  if (s_.box.sheared()) {
    // The offset back within one width (the turns go into the images' keys), and particles that
    // left through a y face into the sliding row: their kinetic energy's jump is the seam's work.
    const double length = s_.box.length(0), slid = s_.box.shear_velocity * s_.time;
    s_.box.shear_turns = static_cast<std::int32_t>(std::floor(slid / length));
    s_.box.shear_offset = slid - s_.box.shear_turns * length;
    for (std::size_t i = 0; i < p.size(); ++i) {
      const double before = p.velocity[i].x;
      s_.box.wrap(p.position[i], p.image[i], &p.velocity[i]);
      if (p.counted(i))
        energy_.seam_crossing_work += 0.5 * p.mass[i] * (p.velocity[i].x * p.velocity[i].x - before * before);
    }
    offset_at_build_ = s_.box.shear_offset;
  } else {
    for (std::size_t i = 0; i < p.size(); ++i) s_.box.wrap(p.position[i], p.image[i]);
  }
  const std::size_t expected_pairs = pairs_.pair_count();
  pairs_ = NeighborPairs{};
  if (domain_) {
    domain_->redistribute(p, kept, kept_walls);  // MPI: particles change ranks, ghosts renewed
    fit_grid_to_domain();
  }
  grid_.bin(p.position);
  const bool sort_now = sort_every_ > 0 && (first || ++rebuilds_since_sort_ >= sort_every_);
  if (sort_now) {
    rebuilds_since_sort_ = 0;
    const std::vector<std::uint32_t> order = grid_.cell_order();
    p.permute(order);
    grid_.bin(p.position);
  }
  if (domain_) domain_->index(p);
  // Pairs within skin of touching, and of an adhesive neck's length further: every pair in contact
  // until the next rebuild (no particle moves more than skin / 2 before it).
  grid_.build_pairs(p, s_.box, s_.skin + s_.cohesion_reach, threads_, pairs_, expected_pairs);
  contacts_.restore(kept, pairs_, p.id, p.image, s_.box.shear_turns);
  ContactStore<State>::sort_kept(kept_walls);
  for (std::size_t w = 0; w < s_.walls.size(); ++w) {
    build_wall_list(w);
    contacts_.restore_wall(w, kept_walls, p.id);
  }
  position_at_build_ = p.position;
  ++stats_.rebuilds;
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::fit_grid_to_domain() {
  const DomainDecomposition& d = domain_->grid();
  const Vec3 box_lo = d.lower(rank_), box_hi = d.upper(rank_);
  Vec3 lo = s_.box.lo, hi = s_.box.hi;
  std::array<bool, 3> cut{};
  for (int a = 0; a < 3; ++a) {
    if (!d.cut(a)) continue;
    const double from = box_lo[a] - d.ghost_width, to = box_hi[a] + d.ghost_width;
    cut[a] = !s_.box.periodic[a] || to - from + 2.0 * cell_size_ < s_.box.length(a);
    if (cut[a]) lo[a] = from, hi[a] = to;
  }
  grid_.setup_region(s_.box, lo, hi, cut, cell_size_, s_.particles.size());
}

template <class Law, bool Rolling>
void DemEngine<Law, Rolling>::pair_forces(double dt) {
  const bool extras = s_.expansion_rate > 0.0 || s_.box.shear_velocity != 0.0;
  if (has_bumps_) {
    if (extras) pair_forces_with<true, true>(dt);
    else pair_forces_with<true, false>(dt);
  } else {
    if (extras) pair_forces_with<false, true>(dt);
    else pair_forces_with<false, false>(dt);
  }
}

template <class Law, bool Rolling>
template <bool Bumps, bool Extras>
void DemEngine<Law, Rolling>::pair_forces_with(double dt) {
  ParticleStore& p = s_.particles;
  const std::size_t n = p.size();
  const auto shifts = s_.box.shift_table();
  const int threads = threads_;
  if (threads > 1 && (thread_force_.size() != static_cast<std::size_t>(threads) || thread_force_[0].size() != n)) {
    thread_force_.assign(threads, std::vector<Vec3>(n));
    thread_torque_.assign(threads, std::vector<Vec3>(n));
    thread_touched_.assign(threads, {});
  }
  ForceLoopSums before;
  before.max_ratio = stats_.max_overlap_ratio;
  const double growth_rate = s_.expansion_rate;
  const bool sliding = s_.box.shear_velocity != 0.0;
  // Each thread owns a contiguous range of particles and adds to their forces directly; a
  // partner owned by another thread gets its share in this thread's buffer (a few percent of
  // the pairs: the particles are sorted by cell, so a range is a slab of space).
  const ForceLoopSums sums =
      reduce_slices(threads, n, before, [&](int t, std::size_t begin, std::size_t end, ForceLoopSums& sum) {
        // Running sums in locals, stored once at the slice's end: through `sum` each contact would
        // store them to memory.
        double max_ratio = 0.0, bump_power = 0.0, growth_power = 0.0, seam_power = 0.0;
        long contacts = 0, begun = 0;
        Vec3* force = p.force.data();
        Vec3* torque = p.torque.data();
        Vec3* foreign_force = threads > 1 ? thread_force_[t].data() : force;
        Vec3* foreign_torque = threads > 1 ? thread_torque_[t].data() : torque;
        std::vector<std::uint32_t>* touched = threads > 1 ? &thread_touched_[t].value : nullptr;
        // The list's walk through raw arrays in locals: a store to a touching flag (a byte, which may
        // alias anything) would otherwise reload every array's address for the next listed pair.
        const Vec3* position = p.position.data();
        const double* radius = p.radius.data();
        const std::uint32_t *offsets = pairs_.offsets.data(), *partner = pairs_.partner.data();
        const std::uint8_t* shift = pairs_.shift.data();
        const Vec3* shift_vector = shifts.data();
        std::uint8_t* touching = contacts_.pair_touching.data();
        for (std::size_t i = begin; i < end; ++i) {
          const Vec3 xi = position[i];
          const double ri = radius[i];
          const long counted = !p.ghost[i];  // a pair is counted on the rank owning its list's particle
          for (std::uint32_t k = offsets[i]; k < offsets[i + 1]; ++k) {
            const std::uint32_t j = partner[k];
            const Vec3 d = xi - (position[j] + shift_vector[shift[k]]);
            const double rj = radius[j];
            const double r2 = norm2(d);
            if (!pair_in_contact(r2, i, j, ri, rj, touching[k])) {
              touching[k] = 0;
              continue;
            }
            if (!touching[k]) {
              touching[k] = 1;
              contacts_.pair_state[k] = State{};
              begun += counted;
            }
            const std::uint8_t code = shift[k];
            // A sliding row's image moves relative to its particle; in a still box no image does.
            const Vec3 image_velocity = Extras ? s_.box.image_velocity(code) : Vec3{};
            const ContactKinematics c = pair_kinematics<Extras>(i, j, d, std::sqrt(r2), image_velocity);
            int bump_face = -1;  // unless one is a wall bump
            if constexpr (Bumps) bump_face = std::max(p.wall[i], p.wall[j]);
            const Params& params = Bumps && bump_face >= 0 ? bump_params_[bump_face] : pair_params_;
            const ContactForce f = Law::force(params, law_state(contacts_.pair_state[k]), c, dt);
            const Vec3 total = f.normal * c.normal + f.tangential;
            const Vec3 arm = cross(c.normal, f.tangential);  // torque = -r n x F_t on both
            force[i] += total;
            torque[i] -= ri * arm;
            Vec3 torque_j = -rj * arm;
            if constexpr (Rolling) {  // a couple: +M on i, -M on j
              const RollingParams& rolling = Bumps && bump_face >= 0 ? bump_rolling_[bump_face] : rolling_.pair;
              const Vec3 m = RollingResistance::torque(rolling, contacts_.pair_state[k].rolling,
                                                       rolling_kinematics(rolling, i, j, c, f.normal), dt);
              torque[i] += m;
              torque_j -= m;
            }
            if (j >= begin && j < end) {
              force[j] -= total;
              torque[j] += torque_j;
            } else {
              foreign_force[j] -= total;
              foreign_torque[j] += torque_j;
              if (touched) touched->push_back(j);
            }
            max_ratio = std::max(max_ratio, c.overlap / (2.0 * std::min(ri, rj)));
            contacts += counted;
            if constexpr (Bumps) {
              if (bump_face >= 0 && counted)  // a bump's work on its free partner, at the bump's velocity
                bump_power += dot(p.wall[i] >= 0 ? -total : total, s_.bump_velocity[bump_face]);
            }
            if constexpr (Extras) {
              if (growth_rate > 0.0 && counted)
                growth_power += f.normal * growth_rate * ((ri < p.target_radius[i]) + (rj < p.target_radius[j]));
              if (sliding && counted)  // F . (v_j's image - v_j): the seam's work
                seam_power += total.x * image_velocity.x;
            }
          }
        }
        sum.max_ratio = max_ratio;
        sum.boundary_power = bump_power;
        sum.growth_power = growth_power;
        sum.seam_power = seam_power;
        sum.contacts = contacts;
        sum.begun = begun;
      });
  if (threads > 1) {  // the buffers' shares, each entry cleared after use (listed once per pair)
    for (int t = 0; t < threads; ++t) {
      for (const std::uint32_t j : thread_touched_[t].value) {
        p.force[j] += thread_force_[t][j];
        p.torque[j] += thread_torque_[t][j];
        thread_force_[t][j] = Vec3{};
        thread_torque_[t][j] = Vec3{};
      }
      thread_touched_[t].value.clear();
    }
  }
  stats_.max_overlap_ratio = sums.max_ratio;
  stats_.contacts = sums.contacts;
  stats_.collisions += sums.begun;
  energy_.wall_power += sums.boundary_power;
  energy_.growth_power += sums.growth_power;
  energy_.seam_power += sums.seam_power;
}

}  // namespace grainflow::dem
