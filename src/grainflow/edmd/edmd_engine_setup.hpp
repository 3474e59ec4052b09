// EdmdEngine's cold members, defined apart from the class so that its header holds the event loop's
// hot paths: laying out its bookkeeping (flights from the particle store, the cell grid, the
// particles sorted by cell) and its reports (the energy budget, the stalled clock's message). Each
// is inline, exactly as it was when defined inside the class (report_stall is never inlined: cold).
// Included at the end of edmd_engine.hpp.
#pragma once

#include "grainflow/edmd/edmd_engine.hpp"

namespace grainflow::edmd {

template <int Dim>
inline engine_api::EnergyBudget EdmdEngine<Dim>::energy_budget() const {
  engine_api::EnergyBudget b;
  b.gravity_work = counters_.start_periodic_potential -
                   engine_api::periodic_potential(s_.particles, s_.box, s_.gravity) + counters_.gravity_shift_work;
  b.wall_work = counters_.wall_work;
  b.boundary_work = counters_.boundary_work;
  b.separation_work = counters_.separation_work;
  b.change = engine_api::mechanical_energy(s_.particles, s_.box, s_.gravity) - counters_.start_energy;
  b.dissipated = counters_.dissipated;
  return b;
}

template <int Dim>
void EdmdEngine<Dim>::report_stall(std::uint32_t i, long long window, double moved) const {
  const ParticleStore& p = s_.particles;
  Stall stall;
  stall.time = s_.time;
  stall.moved = moved;
  stall.events = window;
  stall.i = p.id[i];
  if (event_[i].kind == Kind::pair) stall.j = p.id[event_[i].partner];
  if (event_[i].kind == Kind::wall) stall.wall_face = s_.walls[event_[i].detail].face;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (tc_.last_collision(k) >= stall_.window_start()) {
      ++stall.collider_count;
      if (stall.colliders.size() < 8) stall.colliders.push_back(p.id[k]);
    }
  throw RunError(stall_message(stall, s_));
}

template <int Dim>
inline void EdmdEngine<Dim>::load_flights() {
  ParticleStore& p = s_.particles;
  flight_.assign(p.size(), Flight{});
  rolling_.reset(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    s_.box.wrap(p.position[i], p.image[i]);
    flight_[i].x = p.position[i];
    flight_[i].v = p.velocity[i];
    flight_[i].clock = s_.time;
  }
}

template <int Dim>
inline void EdmdEngine<Dim>::build_grid() {
  const std::size_t n = s_.particles.size();
  const double margin = s_.servo.enabled && s_.servo.scale_width ? 1.1 : 1.0;
  // At most max(32768, 4 N) cells; on the list path max(64, 4 N), as every cell there holds as
  // many slots as the fullest.
  const double max_cells = std::max(use_lists_ ? 64.0 : 32768.0, 4.0 * static_cast<double>(n));
  grid_.reset(s_.box, use_lists_ ? lists_.cell_width() : margin * max_diameter_, max_cells, n);
  for (std::size_t i = 0; i < n; ++i) {
    s_.box.wrap(flight_[i].x, s_.particles.image[i]);
    grid_.insert(flight_, static_cast<int>(i), grid_.cell_of(s_.box, flight_[i].x));
  }
}

template <int Dim>
inline void EdmdEngine<Dim>::sort_by_cell() {
  const std::size_t n = s_.particles.size();
  std::vector<std::uint32_t> order;
  order.reserve(n);
  for (int c = 0; c < static_cast<int>(grid_.size()); ++c)
    for (int j = grid_.head(c); j >= 0; j = flight_[j].next) order.push_back(static_cast<std::uint32_t>(j));
  s_.particles.permute(order);
  load_flights();
  build_grid();
}

}  // namespace grainflow::edmd
