// The soft-sphere engine: velocity Verlet for translation and rotation, cell-grid neighbor lists
// rebuilt when any particle has moved half the skin, pair and wall contacts evaluated by the
// contact law `Law` (a template parameter, so the hot loop inlines it). The heavy members are
// defined in dem_engine_impl.hpp and instantiated once per law, in the law's own .cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <type_traits>
#include <utility>
#include <string>
#include <vector>

#include "grainflow/core/error.hpp"
#include "grainflow/dem/contact_kinematics.hpp"
#include "grainflow/dem/contact_store.hpp"
#include "grainflow/dem/dem_couette_servo.hpp"
#include "grainflow/dem/domain_exchange.hpp"
#include "grainflow/dem/dem_state.hpp"
#include "grainflow/dem/fault_checks.hpp"
#include "grainflow/dem/neighbor_list.hpp"
#include "grainflow/dem/portable_state.hpp"
#include "grainflow/dem/rolling_resistance.hpp"
#include "grainflow/dem/thread_slices.hpp"
#include "grainflow/engine_api/coordination.hpp"
#include "grainflow/engine_api/energy_budget.hpp"

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

// The running sums of the energy budget (engine_api/energy_budget.hpp), this rank's share. Powers are
// those of the last force evaluation; works integrate them over the steps by the trapezoidal rule.
struct EnergyTally {
  double contact_work = 0.0;  // J, all contact forces' work on the free particles (walls' and bumps' included)
  double wall_work = 0.0;     // J, moving walls' and bumps' work: their velocity times the force they exert
  double growth_work = 0.0;   // J, the normal forces' work as radii grow (radius expansion pushes contacts apart)
  // J, Lees–Edwards boundaries: the contact forces across the sliding seam times the rows'
  // velocity jump (part of contact_work), and the kinetic energy a particle gains crossing the seam
  double seam_contact_work = 0.0, seam_crossing_work = 0.0;
  double contact_power = 0.0, wall_power = 0.0, growth_power = 0.0, seam_power = 0.0;  // W
  double start_energy = 0.0;              // J, kinetic + rotational + bounded potential + elastic at the start
  double start_elastic = 0.0;             // J, the springs' part of it
  double start_periodic_potential = 0.0;  // J
};

// One thread's share of a force loop's (pairs' or a wall's) counts, powers and force.
struct ForceLoopSums {
  double max_ratio = 0.0;       // the largest overlap over the smaller diameter
  double boundary_power = 0.0;  // W: on a moving wall, or on free partners by wall bumps
  double growth_power = 0.0, seam_power = 0.0;
  Vec3 force{};   // N: on the particles (a wall's load)
  Vec3 torque{};  // N m: on a wall, about its origin
  long contacts = 0, begun = 0;
  ForceLoopSums& operator+=(const ForceLoopSums& o) {
    max_ratio = std::max(max_ratio, o.max_ratio);
    boundary_power += o.boundary_power;
    growth_power += o.growth_power;
    seam_power += o.seam_power;
    force += o.force;
    torque += o.torque;
    contacts += o.contacts;
    begun += o.begun;
    return *this;
  }
};

// A contact's memory with rolling resistance: the law's and the rolling spring's.
template <class LawState>
struct WithRolling {
  LawState law;
  RollingState rolling;
};

// The rolling resistance of the pairs and of each wall (and its bumps).
struct RollingSetup {
  RollingParams pair;
  std::vector<RollingParams> walls;  // one per DemState wall
};

// `Rolling`: the contacts carry rolling resistance (rolling_resistance.hpp). Without it the
// engine is the same code as before it existed: no memory, no work.
template <class Law, bool Rolling = false>
class DemEngine {
 public:
  using Params = typename Law::Params;
  using State = std::conditional_t<Rolling, WithRolling<typename Law::State>, typename Law::State>;
  static constexpr bool rolling_resistance = Rolling;
  static constexpr bool cohesive = CohesiveContactLaw<Law>;  // contacts outlast touching (adhesion)

  // With `domain` (an MPI run of more than one rank), `state` is the whole initial state, the same
  // on every rank; the engine keeps its slab's particles and copies of the others' near it.
  // `rolling` is read only when Rolling.
  DemEngine(DemState state, Params pair_params, std::vector<Params> wall_params, int threads, int sort_every,
            const EngineDomain* domain = nullptr, RollingSetup rolling = {});

  // This rank's share of the energy budget since the start (sum the ranks' shares). The dissipated
  // energy is what the contact forces took from the particles' relative motion, plus what radius
  // growth put in, less what the springs hold now. The residual is then the integrator's: velocity
  // Verlet against the trapezoidal rule for the forces' work, -dt/4 (v1 - v0).(F1 - F0) a step.
  engine_api::EnergyBudget energy_budget() const;
  const EnergyTally& energy_tally() const { return energy_; }

  DemState& state() { return s_; }
  const DemState& state() const { return s_; }
  const ContactStore<State>& contacts() const { return contacts_; }
  const NeighborPairs& pairs() const { return pairs_; }
  const DemCouetteServo& servo() const { return servo_; }
  ContactStatistics& statistics() { return stats_; }

  // Particles entering and leaving (silos, hoppers): what left through each outlet so far (this
  // rank's particles), and the particles the last exchange removed (their outlet and their state as
  // they left; only the last exchange's, so that a long discharge keeps no record of every grain).
  struct OutletCount {
    long removed = 0;
    double mass = 0.0;  // kg (kg/m for discs)
  };
  struct Removed {
    int outlet = 0;
    ParticleStore::Record particle;
  };
  const std::vector<OutletCount>& outlet_counts() const { return outlet_counts_; }
  std::vector<Removed> take_removed() { return std::exchange(removed_, {}); }  // empty until the next exchange
  // Particles made by an insertion or back from an outlet, still waiting for room.
  std::size_t waiting_count() const { return waiting_.size(); }
  // Particles added and removed from outside between steps (the Python module): applied at the
  // next step's list rebuild, which they force, the energy budget following each in or out as for
  // [[insertion]] and [[outlet]]. An added particle must lie clear of every particle and wall
  // (std::invalid_argument otherwise, nothing added); it gets a new id, returned. Ids not present
  // are ignored. One MPI rank only.
  std::vector<std::uint32_t> add_particles(std::vector<ParticleStore::Record> particles);
  void remove_particles(const std::vector<std::uint32_t>& ids);
  // The MPI side of the engine, or null on one rank.
  const DomainExchange<State>* domain() const { return domain_.get(); }
  // MPI: the ghosts take their owners' state at the step's end (the step refreshes them after the
  // drift, before the second half kick), for observers that evaluate contact forces. Collective.
  void refresh_ghosts() {
    if (domain_) domain_->refresh(s_.particles);
  }

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
    ar(pairs_, contacts_, position_at_build_, rebuilds_since_sort_, stats_, energy_, wall_build_, wall_force_,
       wall_torque_);
    if (s_.box.sheared()) ar(s_.box.shear_offset, s_.box.shear_turns, offset_at_build_);
    if (s_.exchanges) ar(outlet_counts_, waiting_, made_, draws_, next_id_, last_exchange_);
    if (servo_.enabled()) {
      for (auto& wall : s_.walls) wall.motion.serialize(ar);
      servo_.serialize(ar);
    }
    if (domain_) ar(*domain_);  // MPI: a restart runs on as many ranks (checked before)
    for (auto& wall : s_.walls) wall.place(s_.time);  // the shapes where the clock puts them
  }

  // Restarts on another number of MPI ranks (portable_state.hpp).
  using Portable = PortableContacts<State, ContactStatistics>;
  // This rank's share: its own particles, the touching pairs listed under a particle it owns (so
  // that a pair across ranks is taken once), its particles' wall contacts, its counts.
  void portable_share(PortableParticles& particles, Portable& contacts) const;

  // After the engine was built from the portable particles and clock: their contact memory, the
  // last step's forces (the next half kick uses them) and the counters. `totals_here`: this rank
  // keeps the counts of contacts begun (one rank does), so that the ranks' sum stays the run's.
  void restore_portable(const PortableParticles& particles, const Portable& contacts, bool totals_here);

  // One velocity-Verlet step: half kick, drift, walls, (rebuild), forces, half kick.
  void step();

  // Before the first step, after positions or velocities were changed from outside (the Python
  // module): the lists, forces and the energy budget's starting values anew, as the constructor
  // made them.
  void restart_from_current_state();

  // Forces and torques at the current positions; `history_dt` advances the contact histories.
  void compute_forces(double history_dt);

  // Particles and walls each particle touches now (coordination numbers, Lan 1994 Fig. A5.17), by
  // index: one pass over the pair list, however many particles are asked about.
  using Coordination = engine_api::Coordination;
  std::vector<Coordination> coordination() const;

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
        if (!pair_in_contact(r * r, i, j, p.radius[i], p.radius[j], true) || r == 0.0) continue;
        const ContactKinematics c = pair_kinematics(i, j, d, r, s_.box.image_velocity(pairs_.shift[k]));
        const int bump_face = std::max(p.wall[i], p.wall[j]);
        State memory = contacts_.pair_state[k];
        const ContactForce f =
            Law::force(bump_face < 0 ? pair_params_ : bump_params_[bump_face], law_state(memory), c, 0.0);
        const Vec3 force = f.normal * c.normal + f.tangential;  // on i
        if (bump_face < 0) {
          visit(static_cast<std::uint32_t>(i), -1, xj, force);
        } else if (p.wall[i] < 0) {  // a bump's push belongs to its wall: reported on the free partner
          visit(static_cast<std::uint32_t>(i), bump_owner_[bump_face], xj, force);
        } else {
          visit(j, bump_owner_[bump_face], p.position[i] - shifts[pairs_.shift[k]], -force);
        }
      }
    }
    for (std::size_t w = 0; w < s_.walls.size(); ++w) {
      const DemWall& wall = s_.walls[w];
      const auto& list = contacts_.walls[w];
      std::visit(
          [&](const auto& shape) {
            for (std::size_t e = 0; e < list.elements(); ++e)
              for (std::uint32_t k = list.offsets[e]; k < list.offsets[e + 1]; ++k) {
                const std::uint32_t i = list.particle[k];
                if (!list.touching[k] || p.motion[i] != Motion::free || p.ghost[i]) continue;
                const walls::SurfaceContact sc = listed_contact(shape, list, e, k, p.position[i]);
                if (!wall_in_contact(sc.gap, p.radius[i], true, wall_params_[w])) continue;
                Vec3 point = p.position[i] - sc.gap * sc.normal;
                if (wall.face >= 0) point = face_point(wall, p.position[i]);  // exactly on the plane
                const ContactKinematics c =
                    wall_kinematics(i, wall.spins() ? wall.surface_velocity(point) : wall.velocity, sc.normal, sc.gap);
                State memory = list.state[k];
                const ContactForce f = Law::force(wall_params_[w], law_state(memory), c, 0.0);
                visit(i, static_cast<int>(w), point, f.normal * sc.normal + f.tangential);
              }
          },
          wall.shape);
    }
  }

  // N and N m: the force and the torque about its origin the particles exert on wall w at the last
  // force evaluation (this rank's share; N/m and N for discs).
  Vec3 force_on_wall(std::size_t w) const { return -wall_force_[w]; }
  Vec3 torque_on_wall(std::size_t w) const { return wall_torque_[w]; }

  // Positions with periodic crossings undone, for diffusion and outputs.
  Vec3 unwrapped_position(std::size_t i) const {
    return s_.box.unwrapped(s_.particles.position[i], s_.particles.image[i]);
  }

 private:
  // Whether a pair of radii ri, rj at squared distance r2 is in contact: overlapping, or (an adhesive
  // law) touching before and not yet pulled apart past its neck.
  bool pair_in_contact(double r2, std::size_t i, std::size_t j, double ri, double rj, bool touching) const {
    const ParticleStore& p = s_.particles;
    const double sum = ri + rj;
    if constexpr (cohesive) {
      if (touching) {
        const int bump_face = std::max(p.wall[i], p.wall[j]);
        const double reach =
            sum - Law::detach_overlap(bump_face < 0 ? pair_params_ : bump_params_[bump_face], ri * rj / sum);
        return r2 < reach * reach;
      }
    }
    return r2 < sum * sum;
  }
  // The same for a particle whose centre is `gap` from a wall.
  static bool wall_in_contact(double gap, double ri, bool touching, const Params& params) {
    if constexpr (cohesive) {
      if (touching) return gap < ri - Law::detach_overlap(params, ri);
    }
    return gap < ri;
  }
  // The overlap an energy is evaluated at: a neck's negative one for an adhesive law.
  static double energy_overlap(double overlap) {
    if constexpr (cohesive) return overlap;
    else return std::max(0.0, overlap);
  }
  static typename Law::State& law_state(State& s) {
    if constexpr (Rolling) return s.law;
    else return s;
  }
  static const typename Law::State& law_state(const State& s) {
    if constexpr (Rolling) return s.law;
    else return s;
  }
  // What the rolling model reads of particle i touching j (kWall: a wall), with the law's normal
  // force; the rolling inertia only where the epsd dashpot uses it.
  static constexpr std::size_t kWall = ~std::size_t{0};
  RollingKinematics rolling_kinematics(const RollingParams& r, std::size_t i, std::size_t j, const ContactKinematics& c,
                                       double normal_force) const {
    const ParticleStore& p = s_.particles;
    RollingKinematics k;
    k.normal = c.normal;
    k.relative_spin = j == kWall ? p.angular_velocity[i] : p.angular_velocity[i] - p.angular_velocity[j];
    k.effective_radius = c.effective_radius;
    k.normal_force = normal_force;
    if (r.model == RollingModel::epsd && r.damping > 0.0) {
      double inverse = RollingResistance::inverse_rolling_inertia(p.inv_mass[i], p.inv_inertia[i], p.radius[i]);
      if (j != kWall)
        inverse += RollingResistance::inverse_rolling_inertia(p.inv_mass[j], p.inv_inertia[j], p.radius[j]);
      k.rolling_inertia = inverse > 0.0 ? 1.0 / inverse : 0.0;
    }
    return k;
  }

  // The kinematics of the touching pair i, j: d = x_i - x_j (j's image nearest i), r = |d|; velocities
  // as they are now (half-step inside a step), j's image moving `image_velocity` faster than j.
  // Without Sliding the image moves with its particle and `image_velocity` is not read: adding a
  // zero vector is three additions the compiler may not drop (-0 + 0 is +0).
  template <bool Sliding = true>
  ContactKinematics pair_kinematics(std::size_t i, std::size_t j, const Vec3& d, double r,
                                    const Vec3& image_velocity) const {
    const ParticleStore& p = s_.particles;
    const double ri = p.radius[i], rj = p.radius[j];
    ContactKinematics c;
    c.normal = d * (1.0 / r);
    c.overlap = ri + rj - r;
    const Vec3 relative = p.velocity[i] - (Sliding ? p.velocity[j] + image_velocity : p.velocity[j]);
    c.normal_velocity = dot(relative, c.normal);
    c.slip_velocity = relative - c.normal_velocity * c.normal -
                      cross(ri * p.angular_velocity[i] + rj * p.angular_velocity[j], c.normal);
    c.effective_mass = 1.0 / (p.inv_mass[i] + p.inv_mass[j]);
    c.effective_radius = ri * rj / (ri + rj);  // a law that does not read it leaves it to the optimiser
    return c;
  }
  // Particle i touching a wall whose surface moves at `surface` where they touch (unit `normal`
  // from the wall towards the particle), with its centre `gap` from it.
  ContactKinematics wall_kinematics(std::size_t i, const Vec3& surface, const Vec3& normal, double gap) const {
    const ParticleStore& p = s_.particles;
    const double ri = p.radius[i];
    ContactKinematics c;
    c.normal = normal;
    c.overlap = ri - gap;
    const Vec3 relative = p.velocity[i] - surface;
    c.normal_velocity = dot(relative, normal);
    c.slip_velocity = relative - c.normal_velocity * normal - cross(ri * p.angular_velocity[i], normal);
    c.effective_mass = p.mass[i];
    c.effective_radius = ri;
    return c;
  }

  // With `Measure`, returns the contact forces' power on the kicked velocities (contact_power()).
  template <bool Measure>
  double half_kick();

  // W: the contact forces' (all but gravity) power on a free particle of mass m under force f and
  // torque t (gravity g included in f), moving at v and spinning at w. Inline: the half kick calls
  // it per particle.
  static double contact_power_of(const Vec3& f, const Vec3& t, double m, const Vec3& g, const Vec3& v, const Vec3& w) {
    return dot(f - m * g, v) + dot(t, w);
  }
  double contact_power() const;

  // J, what the touching contacts' springs hold now (each pair once, on the rank owning its list's
  // particle; wall contacts with their particle).
  double elastic_energy() const;

  void move_walls();

  void grow_radii();

  bool needs_rebuild() const;

  void rebuild(bool first);

  // MPI: the cells cover this rank's box and its ghost layer only, so that they scale with the
  // rank's particles (the cuts move at a rebalance, so after each exchange). Along a periodic axis
  // whose box and layers would cover the whole length the grid spans and wraps it as on one rank.
  void fit_grid_to_domain();

  void pair_forces(double dt);
  // The pair loop with the terms only some runs need chosen once per evaluation, not tested per
  // pair: `Bumps`, wall bumps exist (their contact parameters and their work on the grains);
  // `Extras`, radii grow or Lees–Edwards rows slide (growth's and the seam's power, the images' velocity).
  template <bool Bumps, bool Extras>
  void pair_forces_with(double dt);

  void wall_forces(double dt);
  // One wall's contacts, its shape's type known at compile time; `Spins`: its surface velocity has
  // a turning part (ω × r).
  template <bool Spins, class Shape>
  ForceLoopSums wall_forces_on(std::size_t w, const Shape& shape, double dt);
  // A mesh's: each particle's contacts with the surface, each in the slot its history is kept in.
  template <bool Spins>
  ForceLoopSums mesh_forces_on(std::size_t w, const walls::MeshWall& mesh, double dt);
  // The force of one wall contact on particle i (its surface contact `sc`, its memory `state`).
  template <bool Spins>
  [[gnu::always_inline]] inline void wall_contact_force(const DemWall& wall, std::size_t w, const Params& params,
                                                        std::uint32_t i, const walls::SurfaceContact& sc,
                                                        State& state, double dt, ForceLoopSums& local);
  // Wall w's contact candidates anew: the free particles within its reach of each element now.
  void build_wall_list(std::size_t w);
  void build_mesh_list(std::size_t w, const walls::MeshWall& mesh);
  // Entry k (of element e) of a wall's list: its contact now, a mesh's as its last evaluation left it.
  template <class Shape>
  static walls::SurfaceContact listed_contact(const Shape& shape, const WallContactList<State>& list, std::size_t e,
                                              std::uint32_t k, const Vec3& x) {
    if constexpr (std::is_same_v<Shape, walls::MeshWall>) return list.contact[k];
    else return shape.contact(static_cast<int>(e), x);
  }
  // Between neighbour-list rebuilds: the lists of the walls whose surface moved more than half a
  // skin since theirs were built, anew, their touching contacts kept.
  void refresh_moved_walls();
  // A box face's point under x, exactly on its plane.
  static Vec3 face_point(const DemWall& wall, const Vec3& x) {
    Vec3 point = x;
    point[wall.axis] = wall.position;
    return point;
  }
  // The Couette servo after a step: the walls' impulse, and an update when one is due.
  void servo_step(double dt);
  // The normal force the particles exert on wall w at the last force evaluation (N; N/m for discs).
  double wall_load(int w) const { return dot(wall_force_[w], s_.walls[w].normal()); }
  // The servo's inputs, over every MPI rank: the bottom and top walls' loads and the contacts
  // begun between particles (one sum; the ranks then steer the walls alike).
  std::array<double, 3> servo_inputs() const {
    std::array<double, 3> v{wall_load(servo_.bottom_wall()), wall_load(servo_.top_wall()),
                            static_cast<double>(stats_.collisions)};
    if (domain_) domain_->sum_in_place(v.data(), v.size());
    return v;
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
  double offset_at_build_ = 0.0;                                 // m, the Lees–Edwards offset the list was built at
  std::vector<std::vector<Vec3>> thread_force_, thread_torque_;  // per thread: shares for others' particles (kept zero)
  std::vector<ThreadSlot<std::vector<std::uint32_t>>> thread_touched_;  // per thread: where those shares are
  std::vector<Vec3> wall_force_;   // N, each wall's force on the particles at the last evaluation
  std::vector<Vec3> wall_torque_;  // N m, the torque on each wall about its origin at the last evaluation
  // Per wall: how far beyond a particle's radius its candidates reach (m), and its displacement and
  // the time when its list was built.
  std::vector<double> wall_reach_;
  std::vector<std::uint8_t> wall_moves_;  // 1: its surface may move (its list's reach is 1.5 skin)
  struct WallBuild {
    Vec3 shift;
    double time = 0.0;
  };
  std::vector<WallBuild> wall_build_;
  // Particles entering and leaving: applied at a rebuild (exchange_particles), whose list then
  // holds the new set.
  // Every kExchangeSteps steps at most (an O(N) pass): new particles are made when an insertion is
  // due, and those waiting placed where there is room.
  static constexpr long kExchangeSteps = 20;
  struct Waiting {
    int insertion = 0;
    ParticleStore::Record particle;
  };
  std::vector<OutletCount> outlet_counts_;
  std::vector<Removed> removed_;
  std::vector<Waiting> waiting_;   // made (or back from an outlet), not yet placed
  std::vector<long> made_;         // per insertion: particles made so far
  std::uint64_t draws_ = 0;        // the insertions' random stream (splitmix64's counter)
  std::uint32_t next_id_ = 0;      // no particle of the run has had it
  long last_exchange_ = -kExchangeSteps;
  std::vector<ParticleStore::Record> requested_in_;  // add_particles, until the next rebuild
  std::vector<std::uint32_t> requested_out_;         // remove_particles: ids
  void count_in(std::size_t i);   // the budget's starting values take particle i's energy on ...
  void count_out(std::size_t i);  // ... or off, at the step the budget counts it
  long due(std::size_t insertion) const;
  bool exchange_due() const;
  void exchange_particles();
  void place_waiting();
  double uniform();
  // -m g.x along the periodic axes (x unwrapped): a particle's share of periodic_potential.
  double periodic_potential_of(double mass, const Vec3& x) const {
    double u = 0.0;
    for (int a = 0; a < 3; ++a)
      if (s_.box.periodic[a]) u -= mass * s_.gravity[a] * x[a];
    return u;
  }
  DemCouetteServo servo_;
  std::array<int, 6> bump_wall_{};                 // wall carrying each face's bumps, -1 when they stand still
  std::array<int, 6> bump_owner_{};                // the bumpy wall of each face, -1 where there is none
  std::array<Params, 6> bump_params_{};            // contact parameters of each face's bumps
  bool has_bumps_ = false;                         // any wall bumps among the particles (from the whole initial state)
  RollingSetup rolling_;                           // Rolling only
  std::array<RollingParams, 6> bump_rolling_{};    // Rolling only: each face's bumps'
  std::unique_ptr<DomainExchange<State>> domain_;  // MPI ranks > 1 only
  ContactStatistics stats_;
  EnergyTally energy_;
};

}  // namespace grainflow::dem
