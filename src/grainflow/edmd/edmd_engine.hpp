// The event-driven engine: exact free flight between binary collisions, one scheduled event per
// particle in an indexed heap, stale events found by per-particle trajectory counters (a particle
// whose scheduled partner changed course is re-predicted when its event comes up), and lazily
// advanced particles (own clocks), so an event costs O(log N). Partners are found in one of two
// ways: where every flight is straight (no gravity, Lees–Edwards boundaries or servo), in
// per-particle neighbour lists rebuilt when a particle has moved a shell from where its list was
// built (see "Neighbour lists" below); elsewhere in the 27 cells, at least a diameter wide, around
// the particle, with cell-crossing events. Dimension 2 (discs in the x-y plane) or 3 is a template
// parameter.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#if defined(__AVX__)
#include <immintrin.h>
#endif
#include <cstdio>
#include <new>
#include <numbers>
#include <string>
#include <vector>

#include "grainflow/core/cell_counts.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/observe/collision_observer.hpp"
#include "grainflow/edmd/couette_servo.hpp"
#include "grainflow/edmd/edmd_state.hpp"
#include "grainflow/edmd/event_counters.hpp"
#include "grainflow/edmd/fault_checks.hpp"
#include "grainflow/edmd/event_queue.hpp"
#include "grainflow/edmd/free_flight.hpp"
#include "grainflow/edmd/stall_detector.hpp"

namespace grainflow::edmd {

// Relative speeds below this fraction of the particles' speeds are round-off (see approaching()).
inline constexpr double kVelocityResolution = 1e-10;

template <int Dim>
class EdmdEngine {
  static_assert(Dim == 2 || Dim == 3);

 public:
  // The event queue keeps a pointer to event_time_: an engine stays where it was built.
  EdmdEngine(const EdmdEngine&) = delete;
  EdmdEngine& operator=(const EdmdEngine&) = delete;

  // `neighbor_lists` = false keeps the cell search where the list path would apply (for tests).
  explicit EdmdEngine(EdmdState state, bool neighbor_lists = true) : s_(std::move(state)) {
    const ParticleStore& p = s_.particles;
    const std::size_t n = p.size();
    last_collision_.assign(n, -kNever);
    event_.assign(n, Event{});
    event_time_.assign(n, kNever);
    for (double r : p.radius) max_diameter_ = std::max(max_diameter_, 2.0 * r);
    const bool one_size = std::all_of(p.radius.begin(), p.radius.end(), [&](double r) { return r == p.radius.front(); });
    uniform_radius_ = one_size && n > 0 ? p.radius.front() : 0.0;
    load_flights();
    stall_.start(s_.time);
    servo_ = CouetteServo(s_);
    shear_velocity_ = s_.lees_edwards_rate * s_.box.length(1);
    lists_ = neighbor_lists && lists_apply();
    build_grid();
    sort_by_cell();
    if (lists_) build_all_lists();
    for (std::size_t i = 0; i < n; ++i) predict(static_cast<std::uint32_t>(i));
    queue_.reset(n, &event_time_);
  }

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
    ar(cells_, cell_size_, head_, prev_, cell_, last_collision_, stall_);
    ar(servo_);
    ar(flight_, center_, inside_, list_, list_cap_, slot_x_, slot_id_, slot_count_, slot_of_, slot_cap_);
    ar(rolling_, rolling_count_, event_, event_time_, queue_, counters_);
    kept_.resize(list_cap_);  // scratch, sized with the lists and slots
    found_.resize(slot_cap_);
  }
  // Whether particles search their neighbour lists (straight flights: no gravity, Lees–Edwards or
  // servo) rather than the 27 cells around them.
  bool neighbor_lists() const { return lists_; }
  const ServoState& servo() const { return servo_.state(); }

  // Reports every later collision to `observer` (nullptr: none). The engine does not own it.
  void set_observer(observe::CollisionObserver* observer) { observer_ = observer; }

  // Calls visit(i, wall, force) for each particle rolling on a wall now (section 2.14.2), with the
  // force the wall exerts on it, m (a - g): the normal part of its weight and, on rough and no-slip
  // walls, the friction that makes it roll (2D: masses per unit depth, as everywhere). It presses on
  // the wall continuously, between collisions, so an observer adds it at its sample times. O(N)
  // while any particle rolls, nothing while none does. Particles must be current (after advance_to).
  template <class Visit>
  void for_each_rolling(Visit&& visit) const {
    if (rolling_count_ == 0) return;
    for (std::size_t i = 0; i < rolling_.size(); ++i)
      if (rolling_[i] >= 0)
        visit(static_cast<std::uint32_t>(i), rolling_[i],
              s_.particles.mass[i] * (acceleration(static_cast<std::uint32_t>(i)) - s_.gravity));
  }

  // Processes every event up to time `t_end`, then brings all particles to `t_end`.
  void advance_to(double t_end) {
    const std::size_t n = s_.particles.size();
    if (n == 0) {
      s_.time = t_end;
      return;
    }
    while (true) {
      const std::uint32_t i = queue_.top();
      const double t = queue_.top_time();  // = event_time_[i], from the heap's own line
      if (!(t <= t_end)) break;
      s_.time = t;
      check_progress(i);
      update_width();
      process(i);
      if (s_.servo.enabled && servo_.due(s_, counters_.collisions)) servo_update();
    }
    synchronize(t_end);
  }

  // The stall detector (stall_detector.hpp) sees every event.
  void check_progress(std::uint32_t i) {
    const std::size_t n = s_.particles.size();
    if (stall_.stalled(n, s_.time)) report_stall(i, StallDetector::window(n), stall_.moved());
  }

  // The stalled clock's message (fault_checks.hpp): the last event's particles and those that
  // collided within the window, found by one pass over the last collision times.
  [[noreturn, gnu::noinline, gnu::cold]] void report_stall(std::uint32_t i, long long window, double moved) const {
    const ParticleStore& p = s_.particles;
    Stall stall;
    stall.time = s_.time;
    stall.moved = moved;
    stall.events = window;
    stall.i = p.id[i];
    if (event_[i].kind == Kind::pair) stall.j = p.id[event_[i].partner];
    if (event_[i].kind == Kind::wall) stall.wall_face = s_.walls[event_[i].detail].face;
    for (std::size_t k = 0; k < p.size(); ++k)
      if (last_collision_[k] >= stall_.window_start()) {
        ++stall.collider_count;
        if (stall.colliders.size() < 8) stall.colliders.push_back(p.id[k]);
      }
    throw RunError(stall_message(stall, s_));
  }

  // Brings every particle to time t (no event may lie before t) and copies positions and velocities
  // back into the particle store, where outputs read them.
  void synchronize(double t) {
    s_.time = t;
    update_width();
    ParticleStore& p = s_.particles;
    for (std::size_t i = 0; i < p.size(); ++i) {
      advance(static_cast<std::uint32_t>(i), t);
      // On the list path particles are wrapped only when their lists are rebuilt: the copy the
      // outputs read must lie in the box (list centres and pair images do not depend on it).
      if (lists_) s_.box.wrap(flight_[i].x, p.image[i]);
      p.position[i] = flight_[i].x;
      p.velocity[i] = flight_[i].v;
    }
    if (s_.servo.enabled) servo_.observe(s_, t);
  }

  // Re-schedules every particle (after walls changed their motion).
  void repredict_all() {
    for (std::size_t i = 0; i < s_.particles.size(); ++i) {
      advance(static_cast<std::uint32_t>(i), s_.time);
      predict(static_cast<std::uint32_t>(i));
      queue_.update(static_cast<std::uint32_t>(i));
    }
  }

 private:
  enum class Kind : std::uint8_t { none, pair, wall, cell, expiry };
  struct Event {
    Kind kind = Kind::none;
    std::int8_t detail = 0;          // wall index, or cell face (axis * 2 + side)
    std::uint32_t partner = 0;
    std::uint32_t partner_count = 0; // partner's trajectory counter when predicted
  };

  // What predicting and advancing a particle reads, in one cache line: an event at 10^6 particles
  // looks at a few dozen partners at random places in memory, one line each instead of one per array.
  struct alignas(64) Flight {
    Vec3 x;                   // m, position at `clock`
    double clock = 0.0;       // s, the particle's own time (lazy advance)
    Vec3 v;                   // m/s, velocity at `clock`
    std::uint32_t count = 0;  // trajectory counter: changes whenever the velocity jumps
    std::int32_t next = -1;   // next particle in the same cell, -1 at the end
  };
  static_assert(sizeof(Flight) == 64);

  void load_flights() {
    ParticleStore& p = s_.particles;
    flight_.assign(p.size(), Flight{});
    rolling_.assign(p.size(), -1);
    rolling_count_ = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      s_.box.wrap(p.position[i], p.image[i]);
      flight_[i].x = p.position[i];
      flight_[i].v = p.velocity[i];
      flight_[i].clock = s_.time;
    }
  }

  // Cells at least a diameter wide; with a shrinking periodic width, 10% spare so the grid lasts.
  void build_grid() {
    const std::size_t n = s_.particles.size();
    const double margin = s_.servo.enabled && s_.servo.scale_width ? 1.1 : 1.0;
    // At most max(32768, 4 N) cells (core/cell_counts.hpp); on the list path max(64, 4 N), as every
    // cell there holds as many slots as the fullest.
    const double max_cells = std::max(lists_ ? 64.0 : 32768.0, 4.0 * static_cast<double>(n));
    const std::array<double, 3> lengths{s_.box.length(0), s_.box.length(1), s_.box.length(2)};
    cells_ = cell_counts(lengths, Dim, lists_ ? list_cell_width() : margin * max_diameter_, 1 << 11, max_cells);
    for (int a = 0; a < 3; ++a) cell_size_[a] = s_.box.length(a) / cells_[a];
    head_.assign(static_cast<std::size_t>(cells_[0]) * cells_[1] * cells_[2], -1);
    prev_.assign(n, -1);
    cell_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      s_.box.wrap(flight_[i].x, s_.particles.image[i]);
      cell_[i] = cell_of(flight_[i].x);
      link(static_cast<int>(i));
    }
  }

  // Stores the particles cell by cell (ids unchanged), so that neighbors sit close in memory: at
  // 10^5 particles and more, a random start order costs a cache miss per partner looked at.
  void sort_by_cell() {
    const std::size_t n = s_.particles.size();
    std::vector<std::uint32_t> order;
    order.reserve(n);
    for (int c = 0; c < static_cast<int>(head_.size()); ++c)
      for (int j = head_[c]; j >= 0; j = flight_[j].next) order.push_back(static_cast<std::uint32_t>(j));
    s_.particles.permute(order);
    load_flights();
    build_grid();
  }

  int cell_of(const Vec3& x) const {
    int c[3] = {0, 0, 0};
    for (int a = 0; a < Dim; ++a)
      c[a] = std::clamp(static_cast<int>(std::floor((x[a] - s_.box.lo[a]) / cell_size_[a])), 0, cells_[a] - 1);
    return c[0] + cells_[0] * (c[1] + cells_[1] * c[2]);
  }

  // The periodic width of a Couette cell whose width follows its gap (CouetteServo::width_at).
  void update_width() {
    if (servo_.width_rate() == 0.0) return;
    s_.box.hi.x = s_.box.lo.x + servo_.width_at(s_.time);
    cell_size_[0] = s_.box.length(0) / cells_[0];
  }
  std::array<int, 3> cell_coordinates(int cell) const {
    return {cell % cells_[0], (cell / cells_[0]) % cells_[1], cell / (cells_[0] * cells_[1])};
  }
  void link(int i) {
    const int c = cell_[i];
    prev_[i] = -1;
    flight_[i].next = head_[c];
    if (head_[c] >= 0) prev_[head_[c]] = i;
    head_[c] = i;
  }
  void unlink(int i) {
    if (prev_[i] >= 0) flight_[prev_[i]].next = flight_[i].next;
    else head_[cell_[i]] = flight_[i].next;
    if (flight_[i].next >= 0) prev_[flight_[i].next] = prev_[i];
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

  bool rolls(std::uint32_t i) const { return rolling_count_ != 0 && rolling_[i] >= 0; }
  void set_rolling(std::uint32_t i, int wall) {
    rolling_count_ += (wall >= 0) - (rolling_[i] >= 0);
    rolling_[i] = wall;
  }

  // Free flight accelerates with gravity; a rolling particle with the tangential part of gravity,
  // reduced by 1/(1 + q) when it rolls without slipping (rough and no-slip walls).
  Vec3 acceleration(std::uint32_t i) const {
    if (!rolls(i)) return s_.gravity;
    const EdmdWall& wall = s_.walls[rolling_[i]];
    Vec3 a = s_.gravity;
    a[wall.axis] = 0.0;
    if (wall.condition == WallCondition::smooth) return a;
    const ParticleStore& p = s_.particles;
    const double q = 1.0 / (p.inv_inertia[i] * p.mass[i] * p.radius[i] * p.radius[i]);
    return a * (1.0 / (1.0 + q));
  }

  // Spin of a particle rolling without slip on its wall: omega x n R = v_t (spin about n kept).
  void roll_without_slip(std::uint32_t i) {
    const EdmdWall& wall = s_.walls[rolling_[i]];
    if (wall.condition == WallCondition::smooth) return;
    ParticleStore& p = s_.particles;
    Vec3 n;
    n[wall.axis] = wall.inward;
    const Vec3 slide = flight_[i].v - wall.velocity;
    const Vec3 spin_about_normal = dot(p.angular_velocity[i], n) * n;
    p.angular_velocity[i] = spin_about_normal + cross(n, slide) * (1.0 / p.radius[i]);
  }

  // Finds i's next event from time s_.time (i must be current).
  void predict(std::uint32_t i) {
    if (lists_) predict_listed(i);
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
    const auto ci = cell_coordinates(cell_[i]);
    // Partners in one cell seen through an image shift; `x_images` also tries the neighboring
    // images along x (a Lees–Edwards row slides by an arbitrary offset, so the nearest image now
    // need not be the one met first).
    auto consider = [&](int cell, const Vec3& shift, const Vec3& shift_velocity, bool x_images) {
      for (int j = head_[cell]; j >= 0; j = flight_[j].next) {
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
    // The neighboring cells are listed first and the first particle of each fetched ahead, so the
    // memory reads for all of them overlap instead of following one another.
    struct Visit {
      int cell, sx, sy, sz;
    };
    std::array<Visit, 27> visits;
    int visit_count = 0;
    const int span_z = Dim == 3 ? 1 : 0;
    for (int dz = -span_z; dz <= span_z; ++dz) {
      int cz = ci[2] + dz, sz = 0;
      if (!wrap_cell(2, cz, sz)) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        int cy = ci[1] + dy, sy = 0;
        if (!wrap_cell(1, cy, sy)) continue;
        if (sy != 0 && shear_velocity_ != 0.0) {
          // Across a Lees–Edwards boundary the image row slides: its x offset is sy * delta(t) and
          // it moves at sy * U. Every cell of that row is searched, so no partner is missed.
          const Vec3 shift{sy * shear_offset(now), sy * s_.box.length(1), sz * s_.box.length(2)};
          const Vec3 shift_velocity{sy * shear_velocity_, 0.0, 0.0};
          for (int cx = 0; cx < cells_[0]; ++cx) consider(cx + cells_[0] * (cy + cells_[1] * cz), shift, shift_velocity, true);
          continue;
        }
        for (int dx = -1; dx <= 1; ++dx) {
          int cx = ci[0] + dx, sx = 0;
          if (!wrap_cell(0, cx, sx)) continue;
          visits[visit_count++] = {cx + cells_[0] * (cy + cells_[1] * cz), sx, sy, sz};
        }
      }
    }
    for (int k = 0; k < visit_count; ++k)
      if (const int first = head_[visits[k].cell]; first >= 0) __builtin_prefetch(&flight_[first]);
    for (int k = 0; k < visit_count; ++k) {
      const Visit& v = visits[k];
      const Vec3 shift{v.sx * s_.box.length(0), v.sy * s_.box.length(1), v.sz * s_.box.length(2)};
      const Vec3 shift_velocity{v.sx * servo_.width_rate(), 0.0, 0.0};  // images move with the width rate
      consider(v.cell, shift, shift_velocity, false);
    }
    for (std::size_t w = 0; w < s_.walls.size(); ++w) {
      if (rolls(i) && rolling_[i] == static_cast<int>(w)) continue;  // rolling on it: no bounces
      const EdmdWall& wall = s_.walls[w];
      const int a = wall.axis;
      const double gap = wall.inward * (xi[a] - wall.at(now)) - ri;
      const double t = closing_time(gap, wall.inward * (vi[a] - wall.velocity[a]), wall.inward * ai[a]);
      if (t < best) {
        best = t;
        e = Event{Kind::wall, static_cast<std::int8_t>(w), 0, 0};
      }
    }
    for (int a = 0; a < Dim; ++a) {
      const bool periodic = s_.box.periodic[a];
      if (cells_[a] == 1 && !periodic) continue;
      const double face_lo = s_.box.lo[a] + ci[a] * cell_size_[a];
      const double face_hi = ci[a] + 1 == cells_[a] ? s_.box.hi[a] : face_lo + cell_size_[a];
      // Faces along x stretch with the periodic width (Couette servo); elsewhere they stand still.
      const double rate_lo = a == 0 ? servo_.width_rate() * ci[a] / cells_[a] : 0.0;
      const double rate_hi = a == 0 ? servo_.width_rate() * (ci[a] + 1) / cells_[a] : 0.0;
      if (ci[a] > 0 || periodic) {
        const double t = closing_time(xi[a] - face_lo, vi[a] - rate_lo, ai[a]);
        if (t < best) {
          best = t;
          e = Event{Kind::cell, static_cast<std::int8_t>(a * 2), 0, 0};
        }
      }
      if (ci[a] + 1 < cells_[a] || periodic) {
        const double t = closing_time(face_hi - xi[a], rate_hi - vi[a], -ai[a]);
        if (t < best) {
          best = t;
          e = Event{Kind::cell, static_cast<std::int8_t>(a * 2 + 1), 0, 0};
        }
      }
    }
    event_[i] = e;
    event_time_[i] = now + best;
  }

  // ---- Neighbour lists (the fast path) ----
  // Without gravity, Lees–Edwards boundaries or a servo-controlled width every particle flies in a
  // straight line, and each one keeps a list of the particles that it can meet: particle i stays
  // within `shell_` of its list centre c_i (its position when the list was built) until an "expiry"
  // event, when its list is rebuilt around where it is then. Two particles whose centres lie more
  // than r_i + r_j + 2 shell apart cannot touch before one of them expires, so i looks for
  // collisions with its list only (about a third of the 27 cells' particles) and crosses no cells.
  // Lists are symmetric: rebuilding i's list removes i from its old neighbours' lists and adds it
  // to its new ones', so a pair is always seen by whichever of the two changes course first. The
  // cell grid (cells >= max diameter + 2 shell) holds the particles by centre, for rebuilds only.
  // The shell trades rebuilds (each scans 27 cells of side d + 2 shell) against longer lists
  // (scanned at every prediction): measured best near 0.3 d at packing 0.47 and 0.45 d at 0.26 (N =
  // 32,000), about 0.2 d plus half the mean free path 1 / (sqrt 2 pi n d^2) (3D) or 1 / (2 sqrt 2 n d) (2D).
  double shell_fraction() const {
    double volume = 1.0;
    for (int a = 0; a < Dim; ++a) volume *= s_.box.length(a);
    const double n = static_cast<double>(s_.particles.size()) / volume;
    const double d = max_diameter_;
    const double free_path = Dim == 3 ? 1.0 / (std::sqrt(2.0) * std::numbers::pi * n * d * d) : 1.0 / (2.0 * std::sqrt(2.0) * n * d);
    return std::clamp(0.2 + 0.5 * free_path / d, 0.2, 0.6);
  }

  double list_cell_width() const { return max_diameter_ + 2.0 * shell_ * (1.0 + 1e-9); }

  bool lists_apply() {
    const std::size_t n = s_.particles.size();
    if (n == 0 || s_.servo.enabled || shear_velocity_ != 0.0 || s_.lees_edwards_rate != 0.0) return false;
    if (!(s_.gravity == Vec3{})) return false;
    shell_ = shell_fraction() * max_diameter_;
    if (!(shell_ > 0.0)) return false;
    for (int a = 0; a < 3; ++a) {
      period_[a] = inv_period_[a] = 0.0;
      if (a < Dim && s_.box.periodic[a]) {
        // Three cells per periodic axis: the 27 searched cells are distinct and the nearest image
        // of any two particles within reach of each other is unique.
        if (s_.box.length(a) < 3.0 * list_cell_width()) return false;
        period_[a] = s_.box.length(a);
        inv_period_[a] = 1.0 / s_.box.length(a);
      }
    }
    return true;
  }

  // Nearest periodic image of a separation (no-op along walled axes and z in 2D).
  Vec3 nearest(Vec3 d) const {
    for (int a = 0; a < Dim; ++a) d[a] -= period_[a] * std::nearbyint(d[a] * inv_period_[a]);
    return d;
  }

  void build_all_lists() {
    const std::size_t n = s_.particles.size();
    center_.resize(n);
    for (std::size_t i = 0; i < n; ++i) center_[i] = flight_[i].x;  // build_grid wrapped them
    inside_.resize(n);
    for (std::size_t i = 0; i < n; ++i) inside_[i] = far_from_faces(static_cast<std::uint32_t>(i));
    slot_cap_ = 8;
    // Coordinates within [-shell, L + shell) rounded to float: each off by 2^-24 of that at most.
    double extent = 0.0;
    for (int a = 0; a < Dim; ++a) extent = std::max(extent, s_.box.length(a) + shell_);
    // Distances are also taken in single precision: a margin of 1e-6 of the extent covers both.
    slot_rounding_ = 1e-6 * (extent + 2.0 * max_diameter_);
    found_.resize(slot_cap_);
    slot_count_.assign(head_.size(), 0);
    slot_x_.assign(head_.size() * slot_cap_ * 3, kFarSlot);
    slot_id_.assign(head_.size() * slot_cap_, 0);
    slot_of_.assign(n, 0);
    for (std::size_t i = 0; i < n; ++i) insert_slot(static_cast<std::uint32_t>(i));
    list_cap_ = 16;
    list_.assign(n * list_cap_, 0);
    kept_.resize(list_cap_);
    for (std::size_t i = 0; i < n; ++i)
      search_neighbors(static_cast<std::uint32_t>(i), [&](std::uint32_t j) {
        if (j > i) {
          push_neighbor(static_cast<std::uint32_t>(i), j);
          push_neighbor(j, static_cast<std::uint32_t>(i));
        }
      });
  }

  // Calls found(j) for every other particle whose centre lies within reach of i's (and perhaps a
  // few just beyond: the cells keep centres in single precision and distances are taken in it, so
  // the reach has a margin for their rounding). Each cell keeps its particles' centres side by side,
  // x, y and z each in a row of slot_cap_ floats (unused slots far away), so that eight are tested
  // at once; a periodic neighbour cell is seen through its shift.
  template <class Found>
  void search_neighbors(std::uint32_t i, Found&& found) {
    const Vec3 ci = center_[i] - s_.box.lo;
    const double ri = radius(static_cast<int>(i));
    const double skin = 2.0 * shell_ * (1.0 + 1e-9) + slot_rounding_;
    const double uniform_reach = 2.0 * uniform_radius_ + skin;
    const float reach2 = static_cast<float>(uniform_reach * uniform_reach);
    const auto c = cell_coordinates(cell_[i]);
    const int span_z = Dim == 3 ? 1 : 0;
    const std::size_t cap = slot_cap_;
    for (int dz = -span_z; dz <= span_z; ++dz) {
      int cz = c[2] + dz, sz = 0;
      if (!wrap_cell(2, cz, sz)) continue;
      for (int dy = -1; dy <= 1; ++dy) {
        int cy = c[1] + dy, sy = 0;
        if (!wrap_cell(1, cy, sy)) continue;
        for (int dx = -1; dx <= 1; ++dx) {
          int cx = c[0] + dx, sx = 0;
          if (!wrap_cell(0, cx, sx)) continue;
          // ci - (cj + shift) = (ci - shift) - cj
          const Vec3 from{ci.x - sx * period_[0], ci.y - sy * period_[1], ci.z - sz * period_[2]};
          const std::size_t cell = static_cast<std::size_t>(cx + cells_[0] * (cy + cells_[1] * cz));
          const float* x = &slot_x_[cell * cap * 3];
          const std::uint32_t* id = &slot_id_[cell * cap];
          const std::uint32_t count = slot_count_[cell];
          if (uniform_radius_ > 0.0) {
#if defined(__AVX__)
            const __m256 fx = _mm256_set1_ps(static_cast<float>(from.x)), fy = _mm256_set1_ps(static_cast<float>(from.y)),
                         fz = _mm256_set1_ps(static_cast<float>(from.z)), r2 = _mm256_set1_ps(reach2);
            for (std::uint32_t k = 0; k < count; k += 8) {
              const __m256 ex = _mm256_sub_ps(fx, _mm256_loadu_ps(x + k));
              const __m256 ey = _mm256_sub_ps(fy, _mm256_loadu_ps(x + cap + k));
              const __m256 ez = _mm256_sub_ps(fz, _mm256_loadu_ps(x + 2 * cap + k));
              const __m256 d2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(ex, ex), _mm256_mul_ps(ey, ey)), _mm256_mul_ps(ez, ez));
              for (unsigned bits = static_cast<unsigned>(_mm256_movemask_ps(_mm256_cmp_ps(d2, r2, _CMP_LT_OQ))); bits != 0;
                   bits &= bits - 1) {
                const std::uint32_t j = id[k + static_cast<std::uint32_t>(__builtin_ctz(bits))];
                if (j != i) found(j);
              }
            }
#else
            std::uint32_t* near = found_.data();  // without branches on the (random) outcome
            std::uint32_t m = 0;
            const float gx = static_cast<float>(from.x), gy = static_cast<float>(from.y), gz = static_cast<float>(from.z);
            for (std::uint32_t k = 0; k < count; ++k) {
              const float ex = gx - x[k], ey = gy - x[cap + k], ez = gz - x[2 * cap + k];
              near[m] = id[k];
              m += (ex * ex + ey * ey + ez * ez < reach2) & (id[k] != i);
            }
            for (std::uint32_t q = 0; q < m; ++q) found(near[q]);
#endif
            continue;
          }
          for (std::uint32_t k = 0; k < count; ++k) {
            const Vec3 d{from.x - x[k], from.y - x[cap + k], from.z - x[2 * cap + k]};
            const double reach = ri + radius(static_cast<int>(id[k])) + skin;
            if (norm2(d) < reach * reach && id[k] != i) found(id[k]);
          }
        }
      }
    }
  }

  void insert_slot(std::uint32_t i) {
    const std::size_t cell = static_cast<std::size_t>(cell_[i]);
    if (slot_count_[cell] == slot_cap_) grow_slots();
    const std::uint32_t k = slot_count_[cell]++;
    const Vec3 c = center_[i] - s_.box.lo;
    float* x = &slot_x_[cell * slot_cap_ * 3];
    x[k] = static_cast<float>(c.x);
    x[slot_cap_ + k] = static_cast<float>(c.y);
    x[2 * slot_cap_ + k] = static_cast<float>(c.z);
    slot_id_[cell * slot_cap_ + k] = i;
    slot_of_[i] = k;
  }

  void remove_slot(std::uint32_t i) {
    const std::size_t cell = static_cast<std::size_t>(cell_[i]);
    float* x = &slot_x_[cell * slot_cap_ * 3];
    std::uint32_t* id = &slot_id_[cell * slot_cap_];
    const std::uint32_t last = --slot_count_[cell], k = slot_of_[i];
    for (std::size_t a = 0; a < 3; ++a) {
      x[a * slot_cap_ + k] = x[a * slot_cap_ + last];
      x[a * slot_cap_ + last] = kFarSlot;
    }
    id[k] = id[last];
    slot_of_[id[k]] = k;
  }

  void grow_slots() {
    const std::size_t cells = slot_count_.size(), cap = slot_cap_ + 8;
    std::vector<float> wider_x(cells * cap * 3, kFarSlot);
    std::vector<std::uint32_t> wider_id(cells * cap, 0);
    for (std::size_t c = 0; c < cells; ++c) {
      for (std::size_t a = 0; a < 3; ++a)
        std::copy_n(slot_x_.begin() + static_cast<std::ptrdiff_t>((c * 3 + a) * slot_cap_), slot_count_[c],
                    wider_x.begin() + static_cast<std::ptrdiff_t>((c * 3 + a) * cap));
      std::copy_n(slot_id_.begin() + static_cast<std::ptrdiff_t>(c * slot_cap_), slot_count_[c],
                  wider_id.begin() + static_cast<std::ptrdiff_t>(c * cap));
    }
    slot_x_.swap(wider_x);
    slot_id_.swap(wider_id);
    slot_cap_ = cap;
    found_.resize(cap);
  }

  // A list is list_cap_ words (a 64-byte line at first): its length, then the neighbours.
  std::uint32_t* list_of(std::uint32_t i) { return list_.data() + static_cast<std::size_t>(i) * list_cap_; }

  // True when i's centre lies so far inside the box along every periodic axis that no particle it
  // can meet is seen through a periodic face: a neighbour's centre is within reach (< 2 max radius
  // + 2 shell) of i's, and any particle strays at most a shell from its centre (synchronize() may
  // wrap one that strayed across a face, which needs its centre within a shell of that face).
  bool far_from_faces(std::uint32_t i) const {
    const double margin = (max_diameter_ + 4.0 * shell_) * (1.0 + 1e-6);
    for (int a = 0; a < Dim; ++a)
      if (period_[a] != 0.0 && (center_[i][a] - s_.box.lo[a] < margin || s_.box.hi[a] - center_[i][a] < margin)) return false;
    return true;
  }

  void push_neighbor(std::uint32_t i, std::uint32_t j) {
    if (list_of(i)[0] + 1 == list_cap_) grow_lists();
    std::uint32_t* list = list_of(i);
    list[++list[0]] = j;
  }

  void grow_lists() {
    const std::size_t n = s_.particles.size(), cap = 2 * list_cap_;
    AlignedWords wider(n * cap);
    for (std::size_t i = 0; i < n; ++i)
      std::copy_n(list_.begin() + static_cast<std::ptrdiff_t>(i * list_cap_), list_[i * list_cap_] + 1,
                  wider.begin() + static_cast<std::ptrdiff_t>(i * cap));
    list_.swap(wider);
    list_cap_ = cap;
    kept_.resize(cap);
  }

  // Where j sits in `list` (it must be there), eight words compared at a time where AVX2 is: the
  // first match past the length word is j's entry, as words past the end come after it.
  std::uint32_t find_in_list(const std::uint32_t* list, std::uint32_t j) const {
#if defined(__AVX2__)
    const __m256i key = _mm256_set1_epi32(static_cast<int>(j));
    unsigned skip = 1;  // the length word
    for (std::uint32_t base = 0;; base += 8, skip = 0) {
      const __m256i words = _mm256_load_si256(reinterpret_cast<const __m256i*>(list + base));
      const unsigned hits = static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(words, key)))) & ~skip;
      if (hits != 0) return base + static_cast<std::uint32_t>(__builtin_ctz(hits));
    }
#else
    std::uint32_t m = 1;
    while (list[m] != j) ++m;
    return m;
#endif
  }

  // Particle i has reached the edge of its shell (and is current): a new list around where it is.
  [[gnu::noinline]] void rebuild_list(std::uint32_t i) {
    ++counters_.list_rebuilds;
    // Old neighbours forget i (their lists fetched together, not one miss after another).
    std::uint32_t* mine = list_of(i);
    for (std::uint32_t k = 1; k <= mine[0]; ++k) __builtin_prefetch(list_of(mine[k]), 1);
    for (std::uint32_t k = 1; k <= mine[0]; ++k) {
      std::uint32_t* theirs = list_of(mine[k]);
      const std::uint32_t m = find_in_list(theirs, i);
      theirs[m] = theirs[theirs[0]--];
    }
    mine[0] = 0;
    s_.box.wrap(flight_[i].x, s_.particles.image[i]);
    remove_slot(i);
    center_[i] = flight_[i].x;
    cell_[i] = cell_of(center_[i]);
    inside_[i] = far_from_faces(i);
    insert_slot(i);
    search_neighbors(i, [&](std::uint32_t j) {
      __builtin_prefetch(list_of(j), 1);
      push_neighbor(i, j);
    });
    for (std::uint32_t k = 1; k <= list_of(i)[0]; ++k) push_neighbor(list_of(i)[k], i);
  }

  // predict() on the list path: the earliest of i's shell expiry, a collision with a listed
  // neighbour and a wall.
  [[gnu::noinline]] void predict_listed(std::uint32_t i) {
    const double now = s_.time;
    const Vec3 xi = flight_[i].x;
    const Vec3 vi = flight_[i].v;
    const double ri = radius(static_cast<int>(i));
    Event e{Kind::expiry, 0, 0, 0};
    double best;
    {  // |d + v t| = shell, with d = x_i - c_i inside the shell: the positive root
      const Vec3 d = nearest(xi - center_[i]);
      const double c = norm2(d) - shell_ * shell_;
      const double b = dot(d, vi);
      const double a = norm2(vi);
      if (c >= 0.0) best = 0.0;
      else if (a == 0.0) best = kNever;
      else {
        const double root = std::sqrt(b * b - a * c);
        best = b > 0.0 ? -c / (b + root) : (root - b) / a;
      }
    }
    const double speed_i = norm(vi);
    const std::uint32_t* list = list_of(i) + 1;
    const std::uint32_t count = list[-1];
    const bool inside = inside_[i] != 0;
    for (std::uint32_t k = 0; k < count; ++k) __builtin_prefetch(&flight_[list[k]]);
    auto separation = [&](const Flight& fj) {
      const Vec3 xj = fj.x + (now - fj.clock) * fj.v;
      return inside ? xi - xj : nearest(xi - xj);
    };
    if (rolling_count_ == 0 && uniform_radius_ > 0.0) {
      // Two passes: the first, without branches on the (random) signs, keeps the neighbours that
      // approach and could touch before the best time so far (the test of contact_time_before(),
      // against the shell expiry); the second solves the few kept exactly.
      const double sigma2 = 4.0 * uniform_radius_ * uniform_radius_;
      const double horizon = -2.0 * best * (1.0 + 1e-9);
      std::uint32_t* kept = kept_.data();  // list_cap_ long
      std::uint32_t m = 0;
      for (std::uint32_t k = 0; k < count; ++k) {
        const Flight& fj = flight_[list[k]];
        const Vec3 d = separation(fj);
        const double b = dot(d, vi - fj.v);
        const double c = norm2(d) - sigma2;
        kept[m] = list[k];
        m += (b < 0.0) & (c <= b * horizon);
      }
      for (std::uint32_t q = 0; q < m; ++q) {
        const std::uint32_t j = kept[q];
        const Flight& fj = flight_[j];
        auto floor = [&] { return kVelocityResolution * (speed_i + norm(fj.v)); };
        const double t = contact_time_before(separation(fj), vi - fj.v, 2.0 * uniform_radius_, best, floor);
        if (t < best) {
          best = t;
          e = Event{Kind::pair, 0, j, fj.count};
        }
      }
    } else {
      for (std::uint32_t k = 0; k < count; ++k) {
        const std::uint32_t j = list[k];
        const Flight& fj = flight_[j];
        const Vec3 d = separation(fj);
        const Vec3 dv = vi - fj.v;
        auto floor = [&] { return kVelocityResolution * (speed_i + norm(fj.v)); };
        const double t = (rolling_count_ == 0 || (!rolls(i) && !rolls(j)))
                             ? contact_time_before(d, dv, ri + radius(static_cast<int>(j)), best, floor)
                             : contact_time_accelerated(d, dv, Vec3{}, ri + radius(static_cast<int>(j)), best, floor());
        if (t < best) {
          best = t;
          e = Event{Kind::pair, 0, j, fj.count};
        }
      }
    }
    for (std::size_t w = 0; w < s_.walls.size(); ++w) {
      if (rolls(i) && rolling_[i] == static_cast<int>(w)) continue;
      const EdmdWall& wall = s_.walls[w];
      const int a = wall.axis;
      const double gap = wall.inward * (xi[a] - wall.at(now)) - ri;
      const double t = closing_time(gap, wall.inward * (vi[a] - wall.velocity[a]), 0.0);
      if (t < best) {
        best = t;
        e = Event{Kind::wall, static_cast<std::int8_t>(w), 0, 0};
      }
    }
    event_[i] = e;
    event_time_[i] = now + best;
  }

  bool wrap_cell(int axis, int& c, int& shift) const {
    if (c >= 0 && c < cells_[axis]) return true;
    if (!s_.box.periodic[axis]) return false;
    shift = c < 0 ? -1 : 1;
    c -= shift * cells_[axis];
    return true;
  }

  void process(std::uint32_t i) {
    ++counters_.events;
    const Event e = event_[i];
    switch (e.kind) {
      case Kind::pair: {
        const std::uint32_t j = e.partner;
        if (lists_) prefetch_collision(i, j);
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
        set_rolling(i, -1);  // a particle collision ends rolling
        set_rolling(j, -1);
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
      __builtin_prefetch(&last_collision_[k]);
    }
    __builtin_prefetch(&flight_[j]);
  }

  // Nearest-image separation x_i - x_j at the current time (Lees–Edwards rows shifted by delta(t)).
  Vec3 displacement(std::uint32_t i, std::uint32_t j) const {
    if (shear_velocity_ == 0.0) return s_.box.minimum_image(flight_[i].x, flight_[j].x);
    Vec3 d = flight_[i].x - flight_[j].x;
    const double k = std::nearbyint(d.y / s_.box.length(1));
    d.y -= k * s_.box.length(1);
    d.x -= k * shear_offset(s_.time);
    d.x -= s_.box.length(0) * std::nearbyint(d.x / s_.box.length(0));
    if (Dim == 3 && s_.box.periodic[2]) d.z -= s_.box.length(2) * std::nearbyint(d.z / s_.box.length(2));
    return d;
  }

  // Velocity of the image of j that i meets: images across a Lees–Edwards boundary slide at U, and
  // images across x move at the width rate of a Couette cell whose width follows its gap. Prediction
  // and resolution must agree on it, or a touching pair is scheduled and skipped for ever.
  Vec3 image_velocity(std::uint32_t i, std::uint32_t j) const {
    Vec3 v;
    const Vec3 d = flight_[i].x - flight_[j].x;
    double rows = 0.0;
    if (shear_velocity_ != 0.0) {
      rows = std::nearbyint(d.y / s_.box.length(1));
      v.x += rows * shear_velocity_;
    }
    if (servo_.width_rate() != 0.0) {
      const double dx = d.x - rows * shear_offset(s_.time);
      v.x += std::nearbyint(dx / s_.box.length(0)) * servo_.width_rate();
    }
    return v;
  }

  // Lees–Edwards offset of the image row above: U t modulo the width (U = shear rate x height).
  double shear_offset(double t) const {
    const double width = s_.box.length(0);
    const double offset = std::fmod(shear_velocity_ * t, width);
    return offset < 0.0 ? offset + width : offset;
  }

  // The servo's update (couette_servo.hpp): new wall speeds from the measured stress, every
  // particle brought to now before the walls change, the width and grid after them, every
  // particle re-predicted.
  void servo_update() {
    if (!servo_.measure(s_, Dim)) return;
    synchronize(s_.time);
    if (servo_.move_walls(s_)) {
      update_width();
      if (cell_size_[0] < max_diameter_) {  // the grid no longer spans a diameter per cell: rebuild it
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
    const bool recent = s_.time - last_collision_[i] < s_.contact_duration || s_.time - last_collision_[j] < s_.contact_duration;
    // Across a Lees–Edwards boundary i meets j's sliding image: resolve in that frame, and measure
    // the energy lost there (in the lab frame the boundary's work would count as well).
    const Vec3 frame = image_velocity(i, j);
    flight_[j].v += frame;
    const double before = kinetic_energy(i) + kinetic_energy(j);
    const Vec3 impulse = collide_pair({flight_[i].v, p.angular_velocity[i], p.radius[i], p.inv_mass[i], p.inv_inertia[i]},
                                      {flight_[j].v, p.angular_velocity[j], p.radius[j], p.inv_mass[j], p.inv_inertia[j]},
                                      normal, recent ? elastic_ : s_.restitution, recent ? -1.0 : s_.tangential_restitution);
    const double lost = before - kinetic_energy(i) - kinetic_energy(j);
    flight_[j].v -= frame;
    last_collision_[i] = last_collision_[j] = s_.time;
    counters_.virial += dot(dr, impulse);
    counters_.dissipated += lost;
    ++flight_[i].count;
    ++flight_[j].count;
    ++counters_.collisions;
    if (observer_ != nullptr) [[unlikely]] report_pair(i, j, impulse, lost);
  }

  // Out of line, so that collide() stays as lean as without an observer: what the collision left
  // unchanged (positions, hence separation, normal and image frame) is recomputed here, and the
  // velocities before are recovered from those after (v_i' = v_i + J/m_i, v_j' = v_j - J/m_j).
  [[gnu::noinline, gnu::cold]] void report_pair(std::uint32_t i, std::uint32_t j, const Vec3& impulse, double lost) {
    const ParticleStore& p = s_.particles;
    const Vec3 dr = displacement(i, j);
    const Vec3 normal = dr * (1.0 / norm(dr));
    const Vec3 frame = image_velocity(i, j);
    observe::PairCollision c;
    c.time = s_.time;
    c.i = i;
    c.j = j;
    c.xi = flight_[i].x;
    c.xj = flight_[i].x - dr;
    c.contact = c.xi - p.radius[i] * normal;
    c.normal = normal;
    c.impulse = impulse;
    c.relative_velocity_before = flight_[i].v - (flight_[j].v + frame) - (p.inv_mass[i] + p.inv_mass[j]) * impulse;
    c.dissipated = lost;
    observer_->on_pair(c);
  }

  void collide_with_wall(std::uint32_t i, int w) {
    const EdmdWall& wall = s_.walls[w];
    ParticleStore& p = s_.particles;
    Vec3 normal;
    normal[wall.axis] = wall.inward;
    // The energy lost is measured in the wall's frame: in the lab frame a moving wall's work on the
    // particle would count as well (and a sheared cell would seem to gain energy in collisions).
    const double before = kinetic_energy(i, wall.velocity);
    const bool recent = s_.time - last_collision_[i] < s_.contact_duration;
    const WallCondition condition = recent ? WallCondition::smooth : wall.condition;
    const Vec3 impulse = collide_wall({flight_[i].v, p.angular_velocity[i], p.radius[i], p.inv_mass[i], p.inv_inertia[i]},
                                      normal, wall.velocity, recent ? elastic_ : wall.restitution, condition);
    servo_.add_normal_impulse(w, dot(impulse, normal));
    last_collision_[i] = s_.time;
    const double lost = before - kinetic_energy(i, wall.velocity);
    counters_.dissipated += lost;
    ++flight_[i].count;
    ++counters_.wall_collisions;
    if (observer_ != nullptr) [[unlikely]] report_wall(i, w, normal, impulse, condition, lost);
    start_rolling_if_slow(i, w);
  }

  // The state before is recovered from that after: v' = v + J/m, and on a rough wall
  // omega' = omega - (R/I) n x J (collide_wall); smooth and no-slip collisions leave the spin.
  [[gnu::noinline, gnu::cold]] void report_wall(std::uint32_t i, int w, const Vec3& normal, const Vec3& impulse,
                                                WallCondition condition, double lost) {
    const EdmdWall& wall = s_.walls[w];
    const ParticleStore& p = s_.particles;
    Vec3 spin = p.angular_velocity[i];
    if (condition == WallCondition::rough) spin += (p.radius[i] * p.inv_inertia[i]) * cross(normal, impulse);
    const Vec3 relative = flight_[i].v - p.inv_mass[i] * impulse - wall.velocity;
    observe::WallCollision c;
    c.time = s_.time;
    c.i = i;
    c.wall = w;
    c.x = flight_[i].x;
    c.contact = c.x;
    c.contact[wall.axis] = wall.at(s_.time);
    c.impulse = impulse;
    c.slip_velocity_before = relative - dot(relative, normal) * normal - p.radius[i] * cross(spin, normal);
    c.dissipated = lost;
    observer_->on_wall(c);
  }

  // Too slow to bounce (section 2.14.2): the particle rolls along the wall until its next particle
  // collision; bouncing ever closer in time would stop the clock.
  void start_rolling_if_slow(std::uint32_t i, int w) {
    const EdmdWall& wall = s_.walls[w];
    ParticleStore& p = s_.particles;
    const double rebound = wall.inward * (flight_[i].v[wall.axis] - wall.velocity[wall.axis]);
    if (rebound >= s_.rolling_speed || wall.velocity[wall.axis] != 0.0) return;
    flight_[i].v[wall.axis] = wall.velocity[wall.axis];
    flight_[i].x[wall.axis] = wall.at(s_.time) + wall.inward * p.radius[i];
    set_rolling(i, w);
    roll_without_slip(i);
    ++flight_[i].count;
    ++counters_.rolling_starts;
  }

  void cross_cell(std::uint32_t i, int axis, bool upward) {
    ++counters_.cell_crossings;
    auto c = cell_coordinates(cell_[i]);
    c[axis] += upward ? 1 : -1;
    ParticleStore& p = s_.particles;
    if (c[axis] < 0 || c[axis] >= cells_[axis]) {  // through a periodic face
      const int k = c[axis] < 0 ? -1 : 1;
      flight_[i].x[axis] -= k * s_.box.length(axis);
      p.image[i][axis] += k;
      c[axis] -= k * cells_[axis];
      if (axis == 1 && shear_velocity_ != 0.0) {
        // Lees–Edwards: the particle becomes its image in the sliding row, shifted and moving with it.
        flight_[i].x.x -= k * shear_offset(s_.time);
        flight_[i].v.x -= k * shear_velocity_;
        const double width = s_.box.length(0);  // back into [lo, hi) along x only: y sits on its face
        const double turns = std::floor((flight_[i].x.x - s_.box.lo.x) / width);
        flight_[i].x.x -= turns * width;
        p.image[i][0] += static_cast<std::int32_t>(turns);
        ++flight_[i].count;
        unlink(static_cast<int>(i));
        cell_[i] = cell_of(flight_[i].x);
        link(static_cast<int>(i));
        return;
      }
      if (axis == 0 && servo_.width_rate() != 0.0) {
        flight_[i].v.x -= k * servo_.width_rate();  // it becomes its image, which moves with the width rate
        ++flight_[i].count;
      }
    }
    unlink(static_cast<int>(i));
    cell_[i] = c[0] + cells_[0] * (c[1] + cells_[1] * c[2]);
    link(static_cast<int>(i));
  }

  // Translational (relative to `frame`) plus rotational kinetic energy of particle i.
  double kinetic_energy(std::uint32_t i, const Vec3& frame = {}) const {
    const ParticleStore& p = s_.particles;
    return 0.5 * p.mass[i] * norm2(flight_[i].v - frame) + 0.5 * norm2(p.angular_velocity[i]) / p.inv_inertia[i];
  }

  EdmdState s_;
  std::array<int, 3> cells_{1, 1, 1};
  Vec3 cell_size_;
  std::vector<int> head_, prev_, cell_;
  std::vector<double> last_collision_;  // s, for the TC model
  double max_diameter_ = 0.0;
  double uniform_radius_ = 0.0;  // m, the radius of every particle, or 0 when sizes differ
  StallDetector stall_;
  double shear_velocity_ = 0.0;  // m/s, Lees–Edwards: velocity of the image row above (shear rate x height)
  CouetteServo servo_;  // the Couette cell's walls and width (also the width law without [servo])
  std::vector<Flight> flight_;
  bool lists_ = false;                   // the neighbour-list path is in use
  double shell_ = 0.0;                   // m, how far a particle moves from its list centre before a rebuild
  Vec3 period_, inv_period_;             // box lengths along periodic axes (0 elsewhere) and inverses
  std::vector<Vec3> center_;             // list centres
  std::vector<std::uint8_t> inside_;     // far_from_faces() at the last rebuild
  template <class T>
  struct LineAllocator {  // 64-byte aligned storage, so each list starts on a cache line
    using value_type = T;
    LineAllocator() = default;
    template <class U>
    LineAllocator(const LineAllocator<U>&) {}
    T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{64})); }
    void deallocate(T* p, std::size_t) { ::operator delete(p, std::align_val_t{64}); }
    bool operator==(const LineAllocator&) const { return true; }
  };
  using AlignedWords = std::vector<std::uint32_t, LineAllocator<std::uint32_t>>;
  std::vector<std::uint32_t> kept_;      // predict_listed()'s scratch: the neighbours worth solving for
  AlignedWords list_;                    // list_cap_ words per particle: count, then neighbours
  std::size_t list_cap_ = 0;
  double slot_rounding_ = 0.0;           // m, bound on the error of a distance between centres in slots
  // Per cell, slot_cap_ (a multiple of 8) slots: list centres from the box's low corner in single
  // precision, rows of x, y and z, and the particles' indices; unused slots lie far away.
  static constexpr float kFarSlot = 1e18f;
  std::vector<float> slot_x_;
  std::vector<std::uint32_t> slot_id_;
  std::vector<std::uint32_t> slot_count_, slot_of_;
  std::size_t slot_cap_ = 0;
  std::vector<std::uint32_t> found_;     // search_neighbors()' scratch, slot_cap_ long
  std::vector<int> rolling_;  // wall a particle rolls on, -1 when free
  long long rolling_count_ = 0;  // particles rolling now: while 0, nobody reads rolling_
  RestitutionLaw elastic_;              // e = 1: TC collisions are elastic and smooth (no dissipation at all)
  std::vector<Event> event_;
  std::vector<double> event_time_;
  EventQueue queue_;
  EventCounters counters_;
  observe::CollisionObserver* observer_ = nullptr;
};

}  // namespace grainflow::edmd
