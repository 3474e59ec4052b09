// The soft-sphere engine: velocity Verlet for translation and rotation, cell-grid neighbor lists
// rebuilt when any particle has moved half the skin, pair and wall contacts evaluated by the
// contact law `Law` (a template parameter, so the hot loop inlines it).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "grainflow/core/error.hpp"
#include "grainflow/dem/contact_kinematics.hpp"
#include "grainflow/dem/contact_store.hpp"
#include "grainflow/dem/domain_exchange.hpp"
#include "grainflow/dem/dem_state.hpp"
#include "grainflow/dem/fault_checks.hpp"
#include "grainflow/dem/neighbor_list.hpp"
#include "grainflow/dem/portable_state.hpp"
#include "grainflow/observe/coordination.hpp"
#include "grainflow/observe/energy_budget.hpp"

namespace grainflow::dem {

// Running statistics the force loop collects for the monitors.
struct ContactStatistics {
  double max_overlap_ratio = 0.0;  // max overlap / smaller diameter since the last reset
  long contacts = 0;               // particle-particle contacts at the last force evaluation
  long wall_contacts = 0;
  long rebuilds = 0;
  long collisions = 0;       // particle-particle contacts begun since the start (Lan's collision count)
  long wall_collisions = 0;  // particle-wall contacts begun since the start
};

// The running sums of the energy budget (observe/energy_budget.hpp), this rank's share. Powers are
// those of the last force evaluation; works integrate them over the steps by the trapezoidal rule.
struct EnergyTally {
  double contact_work = 0.0;  // J, all contact forces' work on the free particles (walls' and bumps' included)
  double wall_work = 0.0;     // J, moving walls' and bumps' work: their velocity times the force they exert
  double growth_work = 0.0;   // J, the normal forces' work as radii grow (radius expansion pushes contacts apart)
  double contact_power = 0.0, wall_power = 0.0, growth_power = 0.0;  // W
  double start_energy = 0.0;            // J, kinetic + rotational + bounded potential + elastic at the start
  double start_elastic = 0.0;           // J, the springs' part of it
  double start_periodic_potential = 0.0;  // J
};

template <class Law>
class DemEngine {
 public:
  using Params = typename Law::Params;
  using State = typename Law::State;

  // With `domain` (an MPI run of more than one rank), `state` is the whole initial state, the same
  // on every rank; the engine keeps its slab's particles and copies of the others' near it.
  DemEngine(DemState state, Params pair_params, std::vector<Params> wall_params, int threads, int sort_every,
            const EngineDomain* domain = nullptr)
      : s_(std::move(state)), pair_params_(pair_params), wall_params_(std::move(wall_params)),
        threads_(std::max(1, threads)), sort_every_(sort_every) {
    s_.particles.ghost.assign(s_.particles.size(), 0);
    contacts_.resize_walls(s_.walls.size(), s_.particles.size());
    bump_wall_.fill(-1);
    bump_params_.fill(pair_params_);
    for (std::size_t w = 0; w < s_.walls.size(); ++w) {
      if (!s_.walls[w].bumpy) continue;
      bump_params_[s_.walls[w].face] = wall_params_[w];  // bumps carry their wall's e and mu
      if (s_.walls[w].motion.moves()) bump_wall_[s_.walls[w].face] = static_cast<int>(w);
    }
    double max_radius = 0.0;
    for (double r : s_.particles.target_radius) max_radius = std::max(max_radius, r);
    cell_size_ = 2.0 * max_radius + s_.skin;
    grid_.setup(s_.box, cell_size_, s_.particles.size());
    if (domain != nullptr && domain->comm->size() > 1) {
      domain_ = std::make_unique<DomainExchange<State>>(*domain->comm, domain->grid);
      domain_->keep_owned(s_.particles, contacts_);
      rank_ = domain->comm->rank();
    }
    for (auto& wall : s_.walls) wall.move_to(s_.time);
    rebuild(true);
    // The initial evaluation must not advance contact histories (no time has passed): dt = 0.
    compute_forces(0.0);
    energy_.contact_power = contact_power();
    energy_.start_elastic = elastic_energy();
    energy_.start_energy = observe::mechanical_energy(s_.particles, s_.box, s_.gravity) + energy_.start_elastic;
    energy_.start_periodic_potential = observe::periodic_potential(s_.particles, s_.box, s_.gravity);
  }

  // This rank's share of the energy budget since the start (sum the ranks' shares). The dissipated
  // energy is what the contact forces took from the particles' relative motion, plus what radius
  // growth put in, less what the springs hold now. The residual is then the integrator's: velocity
  // Verlet against the trapezoidal rule for the forces' work, -dt/4 (v1 - v0).(F1 - F0) a step.
  observe::EnergyBudget energy_budget() const {
    observe::EnergyBudget b;
    const double elastic = elastic_energy();
    b.gravity_work = energy_.start_periodic_potential - observe::periodic_potential(s_.particles, s_.box, s_.gravity);
    b.wall_work = energy_.wall_work;
    b.growth_work = energy_.growth_work;
    b.change = observe::mechanical_energy(s_.particles, s_.box, s_.gravity) + elastic - energy_.start_energy;
    const double relative_work = energy_.contact_work - energy_.wall_work;  // on the contacts' relative motion
    b.dissipated = energy_.growth_work - relative_work - (elastic - energy_.start_elastic);
    return b;
  }
  const EnergyTally& energy_tally() const { return energy_; }

  DemState& state() { return s_; }
  const DemState& state() const { return s_; }
  const ContactStore<State>& contacts() const { return contacts_; }
  const NeighborPairs& pairs() const { return pairs_; }
  ContactStatistics& statistics() { return stats_; }
  // The MPI side of the engine, or null on one rank.
  const DomainExchange<State>* domain() const { return domain_.get(); }

  // Everything that changes as the run goes (checkpoints): the rest follows from the case, so a
  // restart builds the engine from its case first and then reads this over it.
  template <class Archive>
  void serialize(Archive& ar) {
    ar.tag("dem engine");
    ar(s_.particles, s_.time, s_.step, s_.bump_velocity, s_.bump_displacement, s_.expansion_rate);
    std::size_t walls = s_.walls.size();
    ar(walls);
    if (walls != s_.walls.size()) throw RunError("checkpoint: the case has a different number of walls");
    for (auto& wall : s_.walls) ar(wall.position, wall.velocity);
    ar(pairs_, contacts_, position_at_build_, rebuilds_since_sort_, stats_, energy_);
    if (domain_) ar(*domain_);  // MPI: a restart runs on as many ranks (checked before)
  }

  // Restarts on another number of MPI ranks (portable_state.hpp).
  using Portable = PortableContacts<State, ContactStatistics>;
  // This rank's share: its own particles, the touching pairs listed under a particle it owns (so
  // that a pair across ranks is taken once), its particles' wall contacts, its counts.
  void portable_share(PortableParticles& particles, Portable& contacts) const {
    const ParticleStore& p = s_.particles;
    particles.time = s_.time;
    particles.step = s_.step;
    particles.bump_velocity = s_.bump_velocity;
    particles.bump_displacement = s_.bump_displacement;
    particles.expansion_rate = s_.expansion_rate;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.ghost[i]) continue;
      particles.particles.push_back(p.record(i));
      for (std::uint32_t k = pairs_.offsets[i]; k < pairs_.offsets[i + 1]; ++k)
        if (contacts_.pair_touching[k]) {
          const std::uint32_t j = pairs_.partner[k];
          contacts.pairs.push_back({p.id[i], p.id[j], ContactStore<State>::image_key(pairs_.shift[k], p.image[i], p.image[j]),
                                    contacts_.pair_state[k]});
        }
      for (std::size_t w = 0; w < contacts_.wall_state.size(); ++w)
        if (contacts_.wall_touching[w][i])
          contacts.walls.push_back({p.id[i], static_cast<std::uint32_t>(w), contacts_.wall_state[w][i]});
    }
    contacts.stats = stats_;
    contacts.rebuilds_since_sort = rebuilds_since_sort_;
  }

  // After the engine was built from the portable particles and clock: their contact memory, the
  // last step's forces (the next half kick uses them) and the counters. `totals_here`: this rank
  // keeps the counts of contacts begun (one rank does), so that the ranks' sum stays the run's.
  void restore_portable(const PortableParticles& particles, const Portable& contacts, bool totals_here) {
    ParticleStore& p = s_.particles;
    contacts_.restore(contacts.pairs, pairs_, p.id, p.image);
    std::vector<std::int64_t> index(particles.particles.size(), -1);
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.id[i] < index.size()) index[p.id[i]] = static_cast<std::int64_t>(i);
    for (std::size_t w = 0; w < contacts_.wall_state.size(); ++w) {
      std::fill(contacts_.wall_state[w].begin(), contacts_.wall_state[w].end(), State{});
      std::fill(contacts_.wall_touching[w].begin(), contacts_.wall_touching[w].end(), 0);
    }
    for (const auto& c : contacts.walls) {
      const std::int64_t i = c.id < index.size() ? index[c.id] : -1;
      if (i < 0 || p.ghost[i] || c.wall >= contacts_.wall_state.size()) continue;
      contacts_.wall_state[c.wall][i] = c.state;
      contacts_.wall_touching[c.wall][i] = 1;
    }
    for (const auto& r : particles.particles) {
      const std::int64_t i = r.id < index.size() ? index[r.id] : -1;
      if (i < 0) continue;
      p.force[i] = r.force;
      p.torque[i] = r.torque;
    }
    const ContactStatistics now = stats_;  // the contacts touching now, counted at construction
    stats_ = contacts.stats;
    stats_.contacts = now.contacts;
    stats_.wall_contacts = now.wall_contacts;
    if (!totals_here) stats_.collisions = stats_.wall_collisions = 0;
    rebuilds_since_sort_ = contacts.rebuilds_since_sort;
  }

  // One velocity-Verlet step: half kick, drift, walls, (rebuild), forces, half kick.
  void step() {
    ParticleStore& p = s_.particles;
    const double dt = s_.time_step;
    const std::size_t n = p.size();
    half_kick();
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      if (p.motion[i] == Motion::free && !p.ghost[i]) p.position[i] += dt * p.velocity[i];
    s_.time = (s_.step + 1) * dt;  // no accumulated round-off in the clock
    ++s_.step;
    move_walls();
    energy_.growth_work += dt * energy_.growth_power;  // this step's growth against the forces before it
    grow_radii();
    if (domain_) domain_->refresh(p);  // ghosts take their owners' new positions and velocities
    if (domain_ ? domain_->any(needs_rebuild()) : needs_rebuild()) rebuild(false);
    const double contact_before = energy_.contact_power, wall_before = energy_.wall_power;
    compute_forces(dt);
    energy_.contact_power = half_kick(true);
    energy_.contact_work += 0.5 * dt * (contact_before + energy_.contact_power);
    energy_.wall_work += 0.5 * dt * (wall_before + energy_.wall_power);
  }

  // Forces and torques at the current positions; `history_dt` advances the contact histories.
  void compute_forces(double history_dt) {
    ParticleStore& p = s_.particles;
    const std::size_t n = p.size();
    // Gravity, and zero for the non-moving.
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      p.force[i] = p.motion[i] == Motion::free ? p.mass[i] * s_.gravity : Vec3{};
      p.torque[i] = Vec3{};
    }
    energy_.wall_power = energy_.growth_power = 0.0;
    pair_forces(history_dt);
    wall_forces(history_dt);
  }

  // Particles and walls each particle touches now (coordination numbers, Lan 1994 Fig. A5.17), by
  // index: one pass over the pair list, however many particles are asked about.
  using Coordination = observe::Coordination;
  std::vector<Coordination> coordination() const {
    std::vector<Coordination> c(s_.particles.size());
    for (std::size_t a = 0; a + 1 < pairs_.offsets.size(); ++a)
      for (std::uint32_t k = pairs_.offsets[a]; k < pairs_.offsets[a + 1]; ++k)
        if (contacts_.pair_touching[k]) {
          ++c[a].particles;
          ++c[pairs_.partner[k]].particles;
        }
    for (const auto& touching : contacts_.wall_touching)
      for (std::size_t i = 0; i < c.size(); ++i) c[i].walls += touching[i] != 0;
    return c;
  }

  // Each touching contact's force now, once: visit(i, wall, from, force) with the force on particle
  // i and `from` its partner's centre (the periodic image nearest i), or with wall >= 0 the contact
  // point on that wall. Recomputed from the contacts' memory without advancing it (dt = 0): the
  // step's elastic forces, the damping at the full-step velocities. Pairs of two fixed particles
  // (a frozen base pressed into itself) carry no stress and are left out.
  template <class Visit>
  void for_each_contact_force(Visit&& visit) const {
    const ParticleStore& p = s_.particles;
    const auto shifts = s_.box.shift_table();
    for (std::size_t i = 0; i + 1 < pairs_.offsets.size(); ++i) {
      if (p.ghost[i]) continue;
      for (std::uint32_t k = pairs_.offsets[i]; k < pairs_.offsets[i + 1]; ++k) {
        if (!contacts_.pair_touching[k]) continue;
        const std::uint32_t j = pairs_.partner[k];
        if (p.motion[i] != Motion::free && p.motion[j] != Motion::free) continue;
        const Vec3 xj = p.position[j] + shifts[pairs_.shift[k]];
        const Vec3 d = p.position[i] - xj;
        const double r = norm(d);
        if (!(r < p.radius[i] + p.radius[j]) || r == 0.0) continue;
        const ContactKinematics c = pair_kinematics(i, j, d, r);
        const int bump_face = std::max(p.wall[i], p.wall[j]);
        State memory = contacts_.pair_state[k];
        const ContactForce f = Law::force(bump_face < 0 ? pair_params_ : bump_params_[bump_face], memory, c, 0.0);
        visit(static_cast<std::uint32_t>(i), -1, xj, f.normal * c.normal + f.tangential);
      }
    }
    for (std::size_t w = 0; w < s_.walls.size(); ++w) {
      const FlatWall& wall = s_.walls[w];
      Vec3 normal;
      normal[wall.axis] = wall.inward;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (!contacts_.wall_touching[w][i] || p.motion[i] != Motion::free || p.ghost[i]) continue;
        const double gap = wall.inward * (p.position[i][wall.axis] - wall.position);
        if (!(gap < p.radius[i])) continue;
        const ContactKinematics c = wall_kinematics(i, wall, normal, gap);
        State memory = contacts_.wall_state[w][i];
        const ContactForce f = Law::force(wall_params_[w], memory, c, 0.0);
        Vec3 contact = p.position[i];
        contact[wall.axis] = wall.position;
        visit(static_cast<std::uint32_t>(i), static_cast<int>(w), contact, f.normal * normal + f.tangential);
      }
    }
  }

  // Positions with periodic crossings undone, for diffusion and outputs.
  Vec3 unwrapped_position(std::size_t i) const { return s_.box.unwrapped(s_.particles.position[i], s_.particles.image[i]); }

 private:
  // The kinematics of the touching pair i, j: d = x_i - x_j (j's image nearest i), r = |d|; velocities
  // as they are now (half-step inside a step).
  ContactKinematics pair_kinematics(std::size_t i, std::size_t j, const Vec3& d, double r) const {
    const ParticleStore& p = s_.particles;
    const double ri = p.radius[i], rj = p.radius[j];
    ContactKinematics c;
    c.normal = d * (1.0 / r);
    c.overlap = ri + rj - r;
    const Vec3 relative = p.velocity[i] - p.velocity[j];
    c.normal_velocity = dot(relative, c.normal);
    c.slip_velocity = relative - c.normal_velocity * c.normal -
                      cross(ri * p.angular_velocity[i] + rj * p.angular_velocity[j], c.normal);
    c.effective_mass = 1.0 / (p.inv_mass[i] + p.inv_mass[j]);
    c.effective_radius = ri * rj / (ri + rj);  // a law that does not read it leaves it to the optimiser
    return c;
  }
  // Particle i touching `wall` (unit `normal` into the box) with its centre `gap` from it.
  ContactKinematics wall_kinematics(std::size_t i, const FlatWall& wall, const Vec3& normal, double gap) const {
    const ParticleStore& p = s_.particles;
    const double ri = p.radius[i];
    ContactKinematics c;
    c.normal = normal;
    c.overlap = ri - gap;
    const Vec3 relative = p.velocity[i] - wall.velocity;
    c.normal_velocity = dot(relative, normal);
    c.slip_velocity = relative - c.normal_velocity * normal - cross(ri * p.angular_velocity[i], normal);
    c.effective_mass = p.mass[i];
    c.effective_radius = ri;
    return c;
  }

  // With `measure`, returns the contact forces' power on the kicked velocities (contact_power()).
  double half_kick(bool measure = false) {
    ParticleStore& p = s_.particles;
    const double half = 0.5 * s_.time_step;
    const std::size_t n = p.size();
    double power = 0.0;
#pragma omp parallel for num_threads(threads_) schedule(static) reduction(+ : power)
    for (std::size_t i = 0; i < n; ++i) {
      if (p.motion[i] != Motion::free || p.ghost[i]) continue;
      p.velocity[i] += (half * p.inv_mass[i]) * p.force[i];
      p.angular_velocity[i] += (half * p.inv_inertia[i]) * p.torque[i];
      if (measure) power += particle_contact_power(i);
    }
    return power;
  }

  // W: the contact forces' (all but gravity) power on free particle i, torques included.
  double particle_contact_power(std::size_t i) const {
    const ParticleStore& p = s_.particles;
    return dot(p.force[i] - p.mass[i] * s_.gravity, p.velocity[i]) + dot(p.torque[i], p.angular_velocity[i]);
  }
  double contact_power() const {
    double power = 0.0;
    for (std::size_t i = 0; i < s_.particles.size(); ++i)
      if (s_.particles.counted(i)) power += particle_contact_power(i);
    return power;
  }

  // J, what the touching contacts' springs hold now (each pair once, on the rank owning its list's
  // particle; wall contacts with their particle).
  double elastic_energy() const {
    const ParticleStore& p = s_.particles;
    const auto shifts = s_.box.shift_table();
    double e = 0.0;
    for (std::size_t i = 0; i + 1 < pairs_.offsets.size(); ++i) {
      if (p.ghost[i]) continue;
      for (std::uint32_t k = pairs_.offsets[i]; k < pairs_.offsets[i + 1]; ++k) {
        if (!contacts_.pair_touching[k]) continue;
        const std::uint32_t j = pairs_.partner[k];
        const double overlap = p.radius[i] + p.radius[j] - norm(p.position[i] - (p.position[j] + shifts[pairs_.shift[k]]));
        const int bump_face = std::max(p.wall[i], p.wall[j]);
        e += Law::elastic_energy(bump_face < 0 ? pair_params_ : bump_params_[bump_face], contacts_.pair_state[k],
                                 std::max(0.0, overlap), p.radius[i] * p.radius[j] / (p.radius[i] + p.radius[j]));
      }
    }
    for (std::size_t w = 0; w < s_.walls.size(); ++w) {
      const FlatWall& wall = s_.walls[w];
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (!contacts_.wall_touching[w][i] || !p.counted(i)) continue;
        const double overlap = p.radius[i] - wall.inward * (p.position[i][wall.axis] - wall.position);
        e += Law::elastic_energy(wall_params_[w], contacts_.wall_state[w][i], std::max(0.0, overlap), p.radius[i]);
      }
    }
    return e;
  }

  void move_walls() {
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

  void grow_radii() {
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

  bool needs_rebuild() const {
    const ParticleStore& p = s_.particles;
    const double limit = 0.25 * s_.skin * s_.skin;  // (skin / 2)^2
    const std::size_t n = p.size();
    int moved = 0;
#pragma omp parallel for num_threads(threads_) schedule(static) reduction(| : moved)
    for (std::size_t i = 0; i < n; ++i)
      if (!(norm2(p.position[i] - position_at_build_[i]) <= limit)) moved = 1;  // a NaN rebuilds, and is caught there
    return moved != 0;
  }

  void rebuild(bool first) {
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
    if (!first) kept = contacts_.take_touching(pairs_, p.id, p.image);
    for (std::size_t i = 0; i < p.size(); ++i) s_.box.wrap(p.position[i], p.image[i]);
    const std::size_t expected_pairs = pairs_.pair_count();
    pairs_ = NeighborPairs{};
    if (domain_) {
      domain_->redistribute(p, contacts_, kept);  // MPI: particles change ranks, ghosts renewed
      fit_grid_to_domain();
    }
    grid_.bin(p.position);
    const bool sort_now = sort_every_ > 0 && (first || ++rebuilds_since_sort_ >= sort_every_);
    if (sort_now) {
      rebuilds_since_sort_ = 0;
      const std::vector<std::uint32_t> order = grid_.cell_order();
      p.permute(order);
      contacts_.permute_walls(order);
      grid_.bin(p.position);
    }
    if (domain_) domain_->index(p);
    grid_.build_pairs(p, s_.box, s_.skin, threads_, pairs_, expected_pairs);
    contacts_.restore(kept, pairs_, p.id, p.image);
    position_at_build_ = p.position;
    ++stats_.rebuilds;
  }

  // MPI: the cells cover this rank's box and its ghost layer only, so that they scale with the
  // rank's particles (the cuts move at a rebalance, so after each exchange). Along a periodic axis
  // whose box and layers would cover the whole length the grid spans and wraps it as on one rank.
  void fit_grid_to_domain() {
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

  void pair_forces(double dt) {
    ParticleStore& p = s_.particles;
    const std::size_t n = p.size();
    const auto shifts = s_.box.shift_table();
    const int threads = threads_;
    if (threads > 1 && (thread_force_.size() != static_cast<std::size_t>(threads) || thread_force_[0].size() != n)) {
      thread_force_.assign(threads, std::vector<Vec3>(n));
      thread_torque_.assign(threads, std::vector<Vec3>(n));
      thread_touched_.assign(threads, {});
    }
    double max_ratio = stats_.max_overlap_ratio;
    long contacts = 0, begun = 0;
    double bump_power = 0.0, growth_power = 0.0;
    const double growth_rate = s_.expansion_rate;
#pragma omp parallel num_threads(threads) reduction(max : max_ratio) reduction(+ : contacts, begun, bump_power, growth_power)
    {
#ifdef _OPENMP
      const int t = omp_get_thread_num();
#else
      const int t = 0;
#endif
      // Each thread owns a contiguous range of particles and adds to their forces directly; a
      // partner owned by another thread gets its share in this thread's buffer (a few percent of
      // the pairs: the particles are sorted by cell, so a range is a slab of space).
      const std::size_t begin = n * t / threads, end = n * (t + 1) / threads;
      Vec3* force = p.force.data();
      Vec3* torque = p.torque.data();
      Vec3* foreign_force = threads > 1 ? thread_force_[t].data() : force;
      Vec3* foreign_torque = threads > 1 ? thread_torque_[t].data() : torque;
      std::vector<std::uint32_t>* touched = threads > 1 ? &thread_touched_[t] : nullptr;
      for (std::size_t i = begin; i < end; ++i) {
        const Vec3 xi = p.position[i];
        const double ri = p.radius[i];
        const long counted = !p.ghost[i];  // a pair is counted on the rank owning its list's particle
        for (std::uint32_t k = pairs_.offsets[i]; k < pairs_.offsets[i + 1]; ++k) {
          const std::uint32_t j = pairs_.partner[k];
          const Vec3 d = xi - (p.position[j] + shifts[pairs_.shift[k]]);
          const double rj = p.radius[j];
          const double sum = ri + rj;
          const double r2 = norm2(d);
          if (r2 >= sum * sum) {
            contacts_.pair_touching[k] = 0;
            continue;
          }
          if (!contacts_.pair_touching[k]) {
            contacts_.pair_touching[k] = 1;
            contacts_.pair_state[k] = State{};
            begun += counted;
          }
          const ContactKinematics c = pair_kinematics(i, j, d, std::sqrt(r2));
          const int bump_face = std::max(p.wall[i], p.wall[j]);  // -1 unless one is a wall bump
          const Params& params = bump_face < 0 ? pair_params_ : bump_params_[bump_face];
          const ContactForce f = Law::force(params, contacts_.pair_state[k], c, dt);
          const Vec3 total = f.normal * c.normal + f.tangential;
          const Vec3 arm = cross(c.normal, f.tangential);  // torque = -r n x F_t on both
          force[i] += total;
          torque[i] -= ri * arm;
          if (j >= begin && j < end) {
            force[j] -= total;
            torque[j] -= rj * arm;
          } else {
            foreign_force[j] -= total;
            foreign_torque[j] -= rj * arm;
            if (touched) touched->push_back(j);
          }
          max_ratio = std::max(max_ratio, c.overlap / (2.0 * std::min(ri, rj)));
          contacts += counted;
          if (bump_face >= 0 && counted) [[unlikely]]  // a bump's work on its free partner, at the bump's velocity
            bump_power += dot(p.wall[i] >= 0 ? -total : total, s_.bump_velocity[bump_face]);
          if (growth_rate > 0.0 && counted) [[unlikely]]
            growth_power += f.normal * growth_rate * ((ri < p.target_radius[i]) + (rj < p.target_radius[j]));
        }
      }
    }
    if (threads > 1) {  // the buffers' shares, each entry cleared after use (listed once per pair)
      for (int t = 0; t < threads; ++t) {
        for (const std::uint32_t j : thread_touched_[t]) {
          p.force[j] += thread_force_[t][j];
          p.torque[j] += thread_torque_[t][j];
          thread_force_[t][j] = Vec3{};
          thread_torque_[t][j] = Vec3{};
        }
        thread_touched_[t].clear();
      }
    }
    stats_.max_overlap_ratio = max_ratio;
    stats_.contacts = contacts;
    stats_.collisions += begun;
    energy_.wall_power += bump_power;
    energy_.growth_power += growth_power;
  }

  void wall_forces(double dt) {
    ParticleStore& p = s_.particles;
    const std::size_t n = p.size();
    long wall_contacts = 0, begun = 0;
    double max_ratio = stats_.max_overlap_ratio;
    double wall_power = 0.0, growth_power = 0.0;
    const double growth_rate = s_.expansion_rate;
    for (std::size_t w = 0; w < s_.walls.size(); ++w) {
      const FlatWall& wall = s_.walls[w];
      const Params& params = wall_params_[w];
      auto& states = contacts_.wall_state[w];
      auto& touching = contacts_.wall_touching[w];
      Vec3 normal;
      normal[wall.axis] = wall.inward;
#pragma omp parallel for num_threads(threads_) schedule(static) reduction(+ : wall_contacts, begun, wall_power, growth_power) \
    reduction(max : max_ratio)
      for (std::size_t i = 0; i < n; ++i) {
        if (p.motion[i] != Motion::free || p.ghost[i]) continue;  // a ghost meets walls on its own rank
        const double ri = p.radius[i];
        const double gap = wall.inward * (p.position[i][wall.axis] - wall.position);
        if (gap >= ri) {
          touching[i] = 0;
          continue;
        }
        if (!touching[i]) {
          touching[i] = 1;
          states[i] = State{};
          ++begun;
        }
        const ContactKinematics c = wall_kinematics(i, wall, normal, gap);
        const ContactForce f = Law::force(params, states[i], c, dt);
        const Vec3 total = f.normal * normal + f.tangential;
        p.force[i] += total;
        p.torque[i] -= ri * cross(normal, f.tangential);
        wall_power += dot(total, wall.velocity);
        if (growth_rate > 0.0 && ri < p.target_radius[i]) growth_power += f.normal * growth_rate;
        max_ratio = std::max(max_ratio, c.overlap / (2.0 * ri));
        ++wall_contacts;
      }
    }
    stats_.wall_contacts = wall_contacts;
    stats_.wall_collisions += begun;
    stats_.max_overlap_ratio = max_ratio;
    energy_.wall_power += wall_power;
    energy_.growth_power += growth_power;
  }

  DemState s_;
  Params pair_params_;
  std::vector<Params> wall_params_;
  int threads_;
  int sort_every_;
  int rebuilds_since_sort_ = 0;
  CellGrid grid_;
  double cell_size_ = 0.0;  // m: 2 r_max + skin, the reach of a list
  int rank_ = 0;            // MPI: this rank
  NeighborPairs pairs_;
  ContactStore<State> contacts_;
  std::vector<Vec3> position_at_build_;
  std::vector<std::vector<Vec3>> thread_force_, thread_torque_;  // per thread: shares for others' particles (kept zero)
  std::vector<std::vector<std::uint32_t>> thread_touched_;       // per thread: where those shares are
  std::array<int, 6> bump_wall_{};      // wall carrying each face's bumps, -1 when they stand still
  std::array<Params, 6> bump_params_{};  // contact parameters of each face's bumps
  std::unique_ptr<DomainExchange<State>> domain_;  // MPI ranks > 1 only
  ContactStatistics stats_;
  EnergyTally energy_;
};

}  // namespace grainflow::dem
