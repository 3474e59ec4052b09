// The event-driven engine: exact free flight between binary collisions, one scheduled event per
// particle in an indexed heap, stale events found by per-particle trajectory counters (a particle
// whose scheduled partner changed course is re-predicted when its event comes up), and lazily
// advanced particles (own clocks), so an event costs O(log N). Partners are found in one of two
// ways: where every flight is straight (no gravity, Lees–Edwards boundaries or servo), in
// per-particle neighbour lists rebuilt when a particle has moved a shell from where its list was
// built (neighbor_lists.hpp); elsewhere in the 27 cells, at least a diameter wide, around
// the particle, with cell-crossing events. Dimension 2 (discs in the x-y plane) or 3 is a template
// parameter; the entry points are compiled once, in edmd_engine.cpp.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "grainflow/core/error.hpp"
#include "grainflow/engine_api/collision_observer.hpp"
#include "grainflow/edmd/cell_grid.hpp"
#include "grainflow/edmd/collision_reports.hpp"
#include "grainflow/edmd/collision_rules.hpp"
#include "grainflow/edmd/couette_servo.hpp"
#include "grainflow/edmd/edmd_state.hpp"
#include "grainflow/edmd/event_counters.hpp"
#include "grainflow/edmd/event_queue.hpp"
#include "grainflow/edmd/fault_checks.hpp"
#include "grainflow/edmd/flight.hpp"
#include "grainflow/edmd/free_flight.hpp"
#include "grainflow/edmd/lees_edwards.hpp"
#include "grainflow/engine_api/energy_budget.hpp"
#include "grainflow/edmd/neighbor_lists.hpp"
#include "grainflow/edmd/rolling.hpp"
#include "grainflow/edmd/stall_detector.hpp"
#include "grainflow/edmd/tc_model.hpp"

namespace grainflow::edmd {

template <int Dim>
class EdmdEngine {
  static_assert(Dim == 2 || Dim == 3);

 public:
  // The event queue keeps a pointer to event_time_: an engine stays where it was built.
  EdmdEngine(const EdmdEngine&) = delete;
  EdmdEngine& operator=(const EdmdEngine&) = delete;

  // `neighbor_lists` = false keeps the cell search where the list path would apply (for tests).
  explicit EdmdEngine(EdmdState state, bool neighbor_lists = true);

  // The energy budget since the start (engine_api/energy_budget.hpp). Particles must be current (after
  // advance_to). Collisions' losses are measured in the frame of the wall or image met, so the
  // walls' and images' work is the lab-frame energy change beyond that loss: W . J per collision.
  engine_api::EnergyBudget energy_budget() const;

  EdmdState& state() { return s_; }
  const EdmdState& state() const { return s_; }
  EventCounters& counters() { return counters_; }

  // The whole scheduling state, verbatim (checkpoints): every particle's own clock, the predicted
  // events and the heap, cells, lists and servo. Re-predicting from positions instead would round
  // differently and part from the unsplit run. A restart builds the engine from its case first.
  template <class Archive>
  void serialize(Archive& ar) {
    ar.tag(Dim == 3 ? "edmd engine 3d" : "edmd engine 2d");
    ar(s_.particles, s_.box, s_.time, s_.walls);
    ar(grid_, tc_, stall_);
    ar(servo_);
    ar(flight_, lists_);
    ar(rolling_, event_, event_time_, queue_, counters_);
  }
  // Whether particles search their neighbour lists (straight flights: no gravity, Lees–Edwards or
  // servo) rather than the 27 cells around them.
  bool neighbor_lists() const { return use_lists_; }
  const ServoState& servo() const { return servo_.state(); }

  // Reports every later collision to `observer` (nullptr: none). The engine does not own it.
  void set_observer(engine_api::CollisionObserver* observer) { observer_ = observer; }

  // Calls visit(i, wall, force) for each particle rolling on a wall now (section 2.14.2), with the
  // force the wall exerts on it, m (a - g): the normal part of its weight and, on rough and no-slip
  // walls, the friction that makes it roll (2D: masses per unit depth, as everywhere). It presses on
  // the wall continuously, between collisions, so an observer adds it at its sample times. O(N)
  // while any particle rolls, nothing while none does. Particles must be current (after advance_to).
  template <class Visit>
  void for_each_rolling(Visit&& visit) const {
    if (!rolling_.any()) return;
    for (std::size_t i = 0; i < rolling_.size(); ++i)
      if (rolling_.wall(static_cast<std::uint32_t>(i)) >= 0)
        visit(static_cast<std::uint32_t>(i), rolling_.wall(static_cast<std::uint32_t>(i)),
              s_.particles.mass[i] * (acceleration(static_cast<std::uint32_t>(i)) - s_.gravity));
  }

  // Processes every event up to time `t_end`, then brings all particles to `t_end`.
  void advance_to(double t_end) { process_events<false>(t_end, 0); }
  // The same, but stops at the particle collision that brings the count to `collision_limit`
  // (a run's or a segment's budget, counted exactly as Campbell's listings did) and brings all
  // particles to its time. True when it stopped there. kNoCollisionLimit: no limit, and no test
  // per event.
  static constexpr long long kNoCollisionLimit = std::numeric_limits<long long>::max();
  bool advance_to(double t_end, long long collision_limit) {
    if (counters_.collisions >= collision_limit) return true;
    if (collision_limit == kNoCollisionLimit) {
      process_events<false>(t_end, 0);
      return false;
    }
    process_events<true>(t_end, collision_limit);
    return counters_.collisions >= collision_limit;
  }

  // The stall detector (stall_detector.hpp) sees every event.
  void check_progress(std::uint32_t i);

  // The stalled clock's message (fault_checks.hpp): the last event's particles and those that
  // collided within the window, found by one pass over the last collision times.
  [[noreturn, gnu::noinline, gnu::cold]] void report_stall(std::uint32_t i, long long window, double moved) const;

  // Brings every particle to time t (no event may lie before t) and copies positions and velocities
  // back into the particle store, where outputs read them.
  void synchronize(double t);

  // Re-schedules every particle (after walls changed their motion).
  void repredict_all();

  // Velocities written into the store from outside (every particle current): the flights take them,
  // every event is predicted anew, the budget's start moves by the energy added (not work done).
  void take_velocities();

 private:
  template <bool Limited>
  void process_events(double t_end, long long collision_limit);

  enum class Kind : std::uint8_t { none, pair, wall, cell, expiry };
  struct Event {
    Kind kind = Kind::none;
    std::int8_t detail = 0;  // wall index, or cell face (axis * 2 + side)
    std::uint32_t partner = 0;
    std::uint32_t partner_count = 0;  // partner's trajectory counter when predicted
  };

  // Every particle's flight from the particle store, current now, none rolling.
  void load_flights();

  // Cells at least a diameter wide; with a shrinking periodic width, 10% spare so the grid lasts.
  void build_grid();

  // Stores the particles cell by cell (ids unchanged), so that neighbors sit close in memory: at
  // 10^5 particles and more, a random start order costs a cache miss per partner looked at.
  void sort_by_cell();

  // Lists serve where every flight is straight (neighbor_lists.hpp): no gravity, Lees–Edwards
  // boundaries or servo-controlled width.
  bool lists_apply() {
    const std::size_t n = s_.particles.size();
    if (n == 0 || s_.servo.enabled || images_.sliding() || s_.lees_edwards_rate != 0.0 || s_.separation_gap > 0.0)
      return false;
    if (!(s_.gravity == Vec3{})) return false;
    return lists_.configure(s_.box, n, max_diameter_, uniform_radius_);
  }

  // Particle i has reached the edge of its shell (and is current): a new list around where it is.
  [[gnu::noinline]] void rebuild_list(std::uint32_t i) {
    ++counters_.list_rebuilds;
    s_.box.wrap(flight_[i].x, s_.particles.image[i]);
    lists_.rebuild(i, flight_[i].x, s_.box, grid_, s_.particles.radius);
  }

  // The periodic width of a Couette cell whose width follows its gap (CouetteServo::width_at).
  void update_width() {
    if (servo_.width_rate() == 0.0) return;
    s_.box.hi.x = s_.box.lo.x + servo_.width_at(s_.time);
    grid_.stretch_x(s_.box);
  }

  // Moves particle i along its parabola to time t.
  void advance(std::uint32_t i, double t) {
    const double dt = t - flight_[i].clock;
    if (dt == 0.0) return;
    const Vec3 a = acceleration(i);
    flight_[i].x += dt * flight_[i].v + (0.5 * dt * dt) * a;
    flight_[i].v += dt * a;
    flight_[i].clock = t;
    if (rolls(i)) roll_without_slip(i);
  }

  // One particle size needs no look-up in the radius array (a cache miss per partner at 10^6).
  double radius(int j) const { return uniform_radius_ > 0.0 ? uniform_radius_ : s_.particles.radius[j]; }

  bool rolls(std::uint32_t i) const { return rolling_.rolls(i); }

  // Free flight accelerates with gravity, a rolling particle along its wall (rolling.hpp).
  Vec3 acceleration(std::uint32_t i) const {
    if (!rolls(i)) return s_.gravity;
    const ParticleStore& p = s_.particles;
    return rolling_acceleration(s_.gravity, s_.walls[rolling_.wall(i)], p.mass[i], p.inv_inertia[i], p.radius[i]);
  }

  void roll_without_slip(std::uint32_t i) {
    ParticleStore& p = s_.particles;
    p.angular_velocity[i] = rolling_spin(s_.walls[rolling_.wall(i)], flight_[i].v, p.angular_velocity[i], p.radius[i]);
  }

  // Finds i's next event from time s_.time (i must be current).
  void predict(std::uint32_t i) {
    if (use_lists_) predict_listed(i);
    else predict_cells(i);
  }

  // predict() searching the 27 cells around i (kept out of line, as it was before the list path).
  [[gnu::noinline]] void predict_cells(std::uint32_t i) {
    const ParticleStore& p = s_.particles;
    const double now = s_.time;
    double best = kNever;
    Event e;
    const Vec3 xi = flight_[i].x;
    const Vec3 vi = flight_[i].v;
    const Vec3 ai = acceleration(i);
    const double ri = p.radius[i];
    const double speed_i = norm(vi);
    // Partners in the neighboring cells (periodic images through shifted cells).
    const auto ci = grid_.coordinates(grid_.cell(static_cast<int>(i)));
    // Partners in one cell seen through an image shift; `x_images` also tries the neighboring
    // images along x (a Lees–Edwards row slides by an arbitrary offset, so the nearest image now
    // need not be the one met first).
    auto consider = [&](int cell, const Vec3& shift, const Vec3& shift_velocity, bool x_images) {
      for (int j = grid_.head(cell); j >= 0; j = flight_[j].next) {
        if (static_cast<std::uint32_t>(j) == i) continue;
        const double dtj = now - flight_[j].clock;
        const Vec3 aj = acceleration(static_cast<std::uint32_t>(j));
        const Vec3 xj = flight_[j].x + dtj * flight_[j].v + (0.5 * dtj * dtj) * aj + shift;
        const Vec3 vj = flight_[j].v + dtj * aj + shift_velocity;
        auto floor = [&] { return kVelocityResolution * (speed_i + norm(vj)); };
        Vec3 dr = xi - xj;
        const double width = s_.box.length(0);
        if (x_images) dr.x -= width * std::nearbyint(dr.x / width);
        for (int image = x_images ? -1 : 0; image <= (x_images ? 1 : 0); ++image) {
          const Vec3 d{dr.x + image * width, dr.y, dr.z};
          const double t = (!rolls(i) && !rolls(static_cast<std::uint32_t>(j)))
                               ? contact_time_before(d, vi - vj, ri + radius(j), best, floor)
                               : contact_time_accelerated(d, vi - vj, ai - aj, ri + radius(j), best, floor());
          if (t < best) {
            best = t;
            e = Event{Kind::pair, 0, static_cast<std::uint32_t>(j), flight_[j].count};
          }
        }
      }
    };
    grid_.for_each_cell_around(s_.box, ci, flight_, images_, now, servo_.width_rate(), consider);
    earliest_wall(i, xi, vi, ai, ri, best, e);
    int face = 0;
    if (const double t = grid_.exit_time(s_.box, ci, xi, vi, ai, servo_.width_rate(), face); t < best) {
      best = t;
      e = Event{Kind::cell, static_cast<std::int8_t>(face), 0, 0};
    }
    event_[i] = e;
    event_time_[i] = now + best;
  }

  // predict() on the list path: the earliest of i's shell expiry, a collision with a listed
  // neighbour and a wall.
  [[gnu::noinline]] void predict_listed(std::uint32_t i) {
    const double now = s_.time;
    const Vec3 xi = flight_[i].x;
    const Vec3 vi = flight_[i].v;
    const double ri = radius(static_cast<int>(i));
    Event e{Kind::expiry, 0, 0, 0};
    double best = lists_.expiry_time(i, xi, vi);
    const std::span<const std::uint32_t> list = lists_.neighbors(i);
    for (std::uint32_t j : list) __builtin_prefetch(&flight_[j]);
    if (!rolling_.any() && uniform_radius_ > 0.0) {
      if (const std::uint32_t j = lists_.first_contact(i, flight_, xi, vi, now, best); j != lists_.kNone)
        e = Event{Kind::pair, 0, j, flight_[j].count};
    } else {  // sizes differ, or particles roll
      const double speed_i = norm(vi);
      const bool inside = lists_.sees_no_images(i);
      for (std::uint32_t j : list) {
        const Flight& fj = flight_[j];
        const Vec3 xj = fj.x + (now - fj.clock) * fj.v;
        const Vec3 d = inside ? xi - xj : lists_.nearest(xi - xj);
        const Vec3 dv = vi - fj.v;
        auto floor = [&] { return kVelocityResolution * (speed_i + norm(fj.v)); };
        const double t = (!rolling_.any() || (!rolls(i) && !rolls(j)))
                             ? contact_time_before(d, dv, ri + radius(static_cast<int>(j)), best, floor)
                             : contact_time_accelerated(d, dv, Vec3{}, ri + radius(static_cast<int>(j)), best, floor());
        if (t < best) {
          best = t;
          e = Event{Kind::pair, 0, j, fj.count};
        }
      }
    }
    earliest_wall(i, xi, vi, Vec3{}, ri, best, e);  // straight flights
    event_[i] = e;
    event_time_[i] = now + best;
  }

  // Both predictions' walls: the first that i (current, at xi moving at vi and accelerating at ai)
  // reaches before `best`, which it then replaces, with its event. Inlined in each prediction.
  [[gnu::always_inline]] void earliest_wall(std::uint32_t i, const Vec3& xi, const Vec3& vi, const Vec3& ai, double ri,
                                            double& best, Event& e) const {
    const double now = s_.time;
    for (std::size_t w = 0; w < s_.walls.size(); ++w) {
      if (rolls(i) && rolling_.wall(i) == static_cast<int>(w)) continue;  // rolling on it: no bounces
      const EdmdWall& wall = s_.walls[w];
      const int a = wall.axis;
      const double gap = wall.distance(xi, now) - ri;
      const double t = closing_time(gap, wall.inward * (vi[a] - wall.velocity[a]), wall.inward * ai[a]);
      if (t < best) {
        best = t;
        e = Event{Kind::wall, static_cast<std::int8_t>(w), 0, 0};
      }
    }
  }

  void process(std::uint32_t i) {
    ++counters_.events;
    const Event e = event_[i];
    switch (e.kind) {
      case Kind::pair: {
        const std::uint32_t j = e.partner;
        if (use_lists_) prefetch_collision(i, j);
        if (flight_[j].count != e.partner_count) {  // the partner changed course: re-predict i
          ++counters_.stale;
          advance(i, s_.time);
          break;
        }
        advance(i, s_.time);
        advance(j, s_.time);
        // A collision needs approach. Round-off in a root taken at a touching, grazing pair can
        // schedule one for a pair already separating: then there is nothing to resolve.
        const Vec3 dr = displacement(i, j);
        const Vec3 vi = flight_[i].v, vj = flight_[j].v + image_velocity(i, j);
        if (!approaching(dr, vi - vj, kVelocityResolution * (norm(vi) + norm(vj)))) {
          ++counters_.stale;
          predict(j);
          queue_.update(j);
          break;
        }
        rolling_.set(i, -1);  // a particle collision ends rolling
        rolling_.set(j, -1);
        collide(i, j);
        predict(j);
        queue_.update(j);
        break;
      }
      case Kind::wall: {
        advance(i, s_.time);
        const EdmdWall& wall = s_.walls[e.detail];
        const double approach = wall.inward * (flight_[i].v[wall.axis] - wall.velocity[wall.axis]);
        if (approach < 0.0) collide_with_wall(i, e.detail);
        else start_rolling_if_slow(i, e.detail);  // touching and receding too slowly to leave it
        break;
      }
      case Kind::cell:
        advance(i, s_.time);
        cross_cell(i, e.detail / 2, e.detail % 2 == 1);
        break;
      case Kind::expiry:
        advance(i, s_.time);
        rebuild_list(i);
        break;
      case Kind::none:
        break;
    }
    predict(i);
    queue_.update(i);
  }

  // What a collision of i and j reads beside their flights, fetched together up front (at 10^4
  // particles and more each is a cache miss that would otherwise come one after another).
  void prefetch_collision(std::uint32_t i, std::uint32_t j) const {
    const ParticleStore& p = s_.particles;
    for (std::uint32_t k : {i, j}) {
      __builtin_prefetch(&p.angular_velocity[k]);
      __builtin_prefetch(&p.mass[k]);
      __builtin_prefetch(&p.inv_mass[k]);
      __builtin_prefetch(&p.inv_inertia[k]);
      __builtin_prefetch(&p.radius[k]);
      __builtin_prefetch(tc_.last_collision_address(k));
    }
    __builtin_prefetch(&flight_[j]);
  }

  // Nearest-image separation x_i - x_j now, and the velocity of the image of j that i meets
  // (lees_edwards.hpp): prediction and resolution must agree on both.
  Vec3 displacement(std::uint32_t i, std::uint32_t j) const {
    return images_.separation<Dim>(s_.box, flight_[i].x, flight_[j].x, s_.time);
  }
  Vec3 image_velocity(std::uint32_t i, std::uint32_t j) const {
    return images_.image_velocity(s_.box, servo_.width_rate(), flight_[i].x, flight_[j].x, s_.time);
  }

  // The servo's update (couette_servo.hpp): new wall speeds from the measured stress, every
  // particle brought to now before the walls change, the width and grid after them, every
  // particle re-predicted.
  void servo_update() {
    if (!servo_.measure(s_, Dim)) return;
    synchronize(s_.time);
    if (servo_.move_walls(s_)) {
      update_width();
      if (grid_.width(0) < max_diameter_) {  // the grid no longer spans a diameter per cell: rebuild it
        build_grid();
      }
    }
    servo_.finish_update(s_, counters_.collisions);
    ++counters_.servo_updates;
    repredict_all();
  }

  void collide(std::uint32_t i, std::uint32_t j) {
    ParticleStore& p = s_.particles;
    const Vec3 dr = displacement(i, j);
    const Vec3 normal = dr * (1.0 / norm(dr));
    const bool recent = tc_.recent(i, s_.time) || tc_.recent(j, s_.time);
    counters_.tc_collisions += recent;
    // Across a Lees–Edwards boundary i meets j's sliding image: resolve in that frame, and measure
    // the energy lost there (in the lab frame the boundary's work would count as well).
    const Vec3 frame = image_velocity(i, j);
    flight_[j].v += frame;
    const double before = kinetic_energy(i) + kinetic_energy(j);
    const Vec3 impulse =
        collide_pair({flight_[i].v, p.angular_velocity[i], p.radius[i], p.inv_mass[i], p.inv_inertia[i]},
                     {flight_[j].v, p.angular_velocity[j], p.radius[j], p.inv_mass[j], p.inv_inertia[j]}, normal,
                     recent ? tc_.elastic() : s_.restitution, recent ? -1.0 : s_.tangential_restitution);
    const double lost = before - kinetic_energy(i) - kinetic_energy(j);
    flight_[j].v -= frame;
    if (s_.separation_gap > 0.0) [[unlikely]]
      separate(i, j, dr, normal);
    tc_.note_collision(i, s_.time);
    tc_.note_collision(j, s_.time);
    counters_.virial += dot(dr, impulse);
    counters_.dissipated += lost;
    counters_.boundary_work += dot(frame, impulse);  // j's image moved at `frame`: zero inside the box
    ++flight_[i].count;
    ++flight_[j].count;
    ++counters_.collisions;
    if (observer_ != nullptr) [[unlikely]]
      report_pair(i, j, impulse, lost);
  }

  // Out of line, so that collide() stays as lean as without an observer: what the collision left
  // unchanged (positions, hence separation and image frame) is recomputed here (collision_reports.hpp).
  [[gnu::noinline, gnu::cold]] void report_pair(std::uint32_t i, std::uint32_t j, const Vec3& impulse, double lost) {
    const Vec3 dr = displacement(i, j);
    const Collided a = after_collision(i, flight_[i].x, flight_[i].v);
    const Collided b = after_collision(j, flight_[i].x - dr, flight_[j].v + image_velocity(i, j));
    observer_->on_pair(pair_collision_report(s_.time, i, j, a, b, dr, impulse, lost));
  }
  // Particle i as a collision left it, at x moving at v (for a pair's j: those of the image met).
  Collided after_collision(std::uint32_t i, const Vec3& x, const Vec3& v) const {
    const ParticleStore& p = s_.particles;
    return {x, v, p.angular_velocity[i], p.radius[i], p.inv_mass[i], p.inv_inertia[i]};
  }

  void collide_with_wall(std::uint32_t i, int w) {
    const EdmdWall& wall = s_.walls[w];
    ParticleStore& p = s_.particles;
    Vec3 normal;
    normal[wall.axis] = wall.inward;
    // The energy lost is measured in the wall's frame: in the lab frame a moving wall's work on the
    // particle would count as well (and a sheared cell would seem to gain energy in collisions).
    const double before = kinetic_energy(i, wall.velocity);
    const bool recent = tc_.recent(i, s_.time);
    counters_.tc_wall_collisions += recent;
    const WallCondition condition = recent ? WallCondition::smooth : wall.condition;
    const Vec3 impulse =
        collide_wall({flight_[i].v, p.angular_velocity[i], p.radius[i], p.inv_mass[i], p.inv_inertia[i]}, normal,
                     wall.velocity, recent ? tc_.elastic() : wall.restitution, condition);
    servo_.add_normal_impulse(w, dot(impulse, normal));
    if (s_.separation_gap > 0.0) [[unlikely]] {  // Campbell: 1.00001 R from the wall
      const double gap = wall.distance(flight_[i].x, s_.time);
      const double target = (1.0 + s_.separation_gap) * p.radius[i];
      if (gap < target) shift(i, normal * (target - gap));
    }
    tc_.note_collision(i, s_.time);
    const double lost = before - kinetic_energy(i, wall.velocity);
    counters_.dissipated += lost;
    counters_.wall_work += dot(wall.velocity, impulse);
    ++flight_[i].count;
    ++counters_.wall_collisions;
    if (observer_ != nullptr) [[unlikely]]
      report_wall(i, w, normal, impulse, condition, lost);
    start_rolling_if_slow(i, w);
  }

  [[gnu::noinline, gnu::cold]] void report_wall(std::uint32_t i, int w, const Vec3& normal, const Vec3& impulse,
                                                WallCondition condition, double lost) {
    const Collided a = after_collision(i, flight_[i].x, flight_[i].v);
    observer_->on_wall(wall_collision_report(s_.time, i, w, s_.walls[w], a, normal, impulse, condition, lost));
  }

  // Too slow to bounce (section 2.14.2): the particle rolls along the wall until its next particle
  // collision; bouncing ever closer in time would stop the clock.
  void start_rolling_if_slow(std::uint32_t i, int w) {
    const EdmdWall& wall = s_.walls[w];
    ParticleStore& p = s_.particles;
    const double rebound = wall.inward * (flight_[i].v[wall.axis] - wall.velocity[wall.axis]);
    if (rebound >= s_.rolling_speed || wall.velocity[wall.axis] != 0.0) return;
    // The normal rebound, the spin that does not roll and the gap to the wall go: a last, perfectly
    // inelastic impact, whose energy counts as dissipated.
    const double before = particle_energy(i);
    flight_[i].v[wall.axis] = wall.velocity[wall.axis];
    flight_[i].x[wall.axis] = wall.at(s_.time) + wall.inward * p.radius[i];
    rolling_.set(i, w);
    roll_without_slip(i);
    counters_.dissipated += before - particle_energy(i);
    ++flight_[i].count;
    ++counters_.rolling_starts;
  }

  void cross_cell(std::uint32_t i, int axis, bool upward) {
    ++counters_.cell_crossings;
    auto c = grid_.coordinates(grid_.cell(static_cast<int>(i)));
    c[axis] += upward ? 1 : -1;
    ParticleStore& p = s_.particles;
    if (c[axis] < 0 || c[axis] >= grid_.count(axis)) {  // through a periodic face
      const int k = c[axis] < 0 ? -1 : 1;
      flight_[i].x[axis] -= k * s_.box.length(axis);
      p.image[i][axis] += k;
      c[axis] -= k * grid_.count(axis);
      if (axis == 1 && images_.sliding()) {
        // Lees–Edwards: the particle becomes its image in the sliding row, shifted and moving with it;
        // the boundary's work is the energy of that change of velocity.
        const double before = kinetic_energy(i);
        counters_.gravity_shift_work += p.mass[i] * s_.gravity.x * k * images_.offset(s_.box.length(0), s_.time);
        p.image[i][0] += static_cast<std::int32_t>(images_.enter_row(s_.box, k, s_.time, flight_[i].x, flight_[i].v));
        counters_.boundary_work += kinetic_energy(i) - before;
        ++flight_[i].count;
        grid_.move(flight_, static_cast<int>(i), grid_.cell_of(s_.box, flight_[i].x));
        return;
      }
      if (axis == 0 && servo_.width_rate() != 0.0) {
        const double before = kinetic_energy(i);
        flight_[i].v.x -= k * servo_.width_rate();  // it becomes its image, which moves with the width rate
        counters_.boundary_work += kinetic_energy(i) - before;
        ++flight_[i].count;
      }
    }
    grid_.move(flight_, static_cast<int>(i), grid_.index(c[0], c[1], c[2]));
  }

  // Translational (relative to `frame`) plus rotational kinetic energy of particle i.
  double kinetic_energy(std::uint32_t i, const Vec3& frame = {}) const {
    const ParticleStore& p = s_.particles;
    return 0.5 * p.mass[i] * norm2(flight_[i].v - frame) + 0.5 * norm2(p.angular_velocity[i]) / p.inv_inertia[i];
  }

  // Campbell's guard against pairs that would meet again at once (listings COL001/COL002): the pair
  // is pushed apart along the normal to (1 + gap) times the contact distance, each by its partner's
  // share of the mass (the centre of mass stays).
  void separate(std::uint32_t i, std::uint32_t j, const Vec3& dr, const Vec3& normal) {
    const ParticleStore& p = s_.particles;
    const double deficit = (1.0 + s_.separation_gap) * (p.radius[i] + p.radius[j]) - norm(dr);
    if (!(deficit > 0.0)) return;
    const double share_i = p.inv_mass[i] / (p.inv_mass[i] + p.inv_mass[j]);
    shift(i, normal * (deficit * share_i));
    shift(j, normal * (-deficit * (1.0 - share_i)));
  }
  // Moves particle i by `by` now (it is current): into its cell, its course changed. The shift's
  // gravitational energy -m g.by (along every axis: along a periodic one gravity's work is counted
  // from the unwrapped displacement) is the separation's work in the energy budget.
  void shift(std::uint32_t i, const Vec3& by) {
    ParticleStore& p = s_.particles;
    flight_[i].x += by;
    s_.box.wrap(flight_[i].x, p.image[i]);
    counters_.separation_work -= p.mass[i] * dot(s_.gravity, by);
    ++flight_[i].count;
    const int cell = grid_.cell_of(s_.box, flight_[i].x);
    if (cell != grid_.cell(static_cast<int>(i))) grid_.move(flight_, static_cast<int>(i), cell);
  }

  // Its kinetic energy and potential along the bounded axes (engine_api/energy_budget.hpp).
  double particle_energy(std::uint32_t i) const {
    return kinetic_energy(i) + engine_api::bounded_potential(s_.box, s_.gravity, s_.particles.mass[i], flight_[i].x);
  }

  EdmdState s_;
  CellGrid<Dim> grid_;
  TcModel tc_;
  double max_diameter_ = 0.0;
  double uniform_radius_ = 0.0;  // m, the radius of every particle, or 0 when sizes differ
  StallDetector stall_;
  LeesEdwardsImages images_;
  CouetteServo servo_;          // the Couette cell's walls and width (also the width law without [servo])
  std::vector<Flight> flight_;  // flight.hpp
  bool use_lists_ = false;      // the neighbour-list path is in use
  NeighborLists<Dim> lists_;
  RollingWalls rolling_;
  std::vector<Event> event_;
  std::vector<double> event_time_;
  EventQueue queue_;
  EventCounters counters_;
  engine_api::CollisionObserver* observer_ = nullptr;
};

}  // namespace grainflow::edmd

#include "grainflow/edmd/edmd_engine_setup.hpp"
