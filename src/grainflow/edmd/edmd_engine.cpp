// The event-driven engine's entry points (construction, the event loop, synchronisation),
// compiled here once for each dimension: every file that runs an engine links to these instead
// of compiling the event loop again.
#include "grainflow/edmd/edmd_engine.hpp"

namespace grainflow::edmd {

template <int Dim>
EdmdEngine<Dim>::EdmdEngine(EdmdState state, bool neighbor_lists) : s_(std::move(state)) {
  const ParticleStore& p = s_.particles;
  const std::size_t n = p.size();
  tc_.reset(n, s_.contact_duration);
  event_.assign(n, Event{});
  event_time_.assign(n, kNever);
  for (double r : p.radius) max_diameter_ = std::max(max_diameter_, 2.0 * r);
  const bool one_size = std::all_of(p.radius.begin(), p.radius.end(), [&](double r) { return r == p.radius.front(); });
  uniform_radius_ = one_size && n > 0 ? p.radius.front() : 0.0;
  load_flights();
  stall_.start(s_.time);
  servo_ = CouetteServo(s_);
  images_.shear_velocity = s_.lees_edwards_rate * s_.box.length(1);
  use_lists_ = neighbor_lists && lists_apply();
  build_grid();
  sort_by_cell();
  if (use_lists_) lists_.build(s_.box, grid_, flight_, s_.particles.radius);
  for (std::size_t i = 0; i < n; ++i) predict(static_cast<std::uint32_t>(i));
  queue_.reset(n, &event_time_);
  counters_.start_energy = engine_api::mechanical_energy(p, s_.box, s_.gravity);
  counters_.start_periodic_potential = engine_api::periodic_potential(p, s_.box, s_.gravity);
}

template <int Dim>
template <bool Limited>
void EdmdEngine<Dim>::process_events(double t_end, long long collision_limit) {
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
    if constexpr (Limited) {
      if (counters_.collisions >= collision_limit) {
        t_end = t;
        break;
      }
    }
  }
  synchronize(t_end);
}

template <int Dim>
void EdmdEngine<Dim>::check_progress(std::uint32_t i) {
  const std::size_t n = s_.particles.size();
  if (stall_.stalled(n, s_.time)) report_stall(i, StallDetector::window(n), stall_.moved());
}

template <int Dim>
void EdmdEngine<Dim>::synchronize(double t) {
  s_.time = t;
  update_width();
  ParticleStore& p = s_.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    advance(static_cast<std::uint32_t>(i), t);
    // On the list path particles are wrapped only when their lists are rebuilt: the copy the
    // outputs read must lie in the box (list centres and pair images do not depend on it).
    if (use_lists_) s_.box.wrap(flight_[i].x, p.image[i]);
    p.position[i] = flight_[i].x;
    p.velocity[i] = flight_[i].v;
  }
  if (s_.servo.enabled) servo_.observe(s_, t);
}

template <int Dim>
void EdmdEngine<Dim>::repredict_all() {
  for (std::size_t i = 0; i < s_.particles.size(); ++i) {
    advance(static_cast<std::uint32_t>(i), s_.time);
    predict(static_cast<std::uint32_t>(i));
    queue_.update(static_cast<std::uint32_t>(i));
  }
}
template <int Dim>
void EdmdEngine<Dim>::take_velocities() {
  const ParticleStore& p = s_.particles;
  double added = 0.0;  // J: the kinetic energy the new velocities bring
  for (std::size_t i = 0; i < p.size(); ++i) {
    advance(static_cast<std::uint32_t>(i), s_.time);
    added += 0.5 * p.mass[i] * (dot(p.velocity[i], p.velocity[i]) - dot(flight_[i].v, flight_[i].v));
    flight_[i].v = p.velocity[i];
  }
  repredict_all();
  counters_.start_energy += added;
}

template class EdmdEngine<2>;
template class EdmdEngine<3>;
template void EdmdEngine<2>::process_events<false>(double, long long);
template void EdmdEngine<2>::process_events<true>(double, long long);
template void EdmdEngine<3>::process_events<false>(double, long long);
template void EdmdEngine<3>::process_events<true>(double, long long);

}  // namespace grainflow::edmd
