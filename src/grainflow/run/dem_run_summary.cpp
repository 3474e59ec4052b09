#include <algorithm>
#include <string>

#include "grainflow/core/version.hpp"
#include "grainflow/run/dem_run_stages.hpp"

namespace grainflow::run {

// summary.json: what the run was, its means over the averaging window, its faults and warnings.
void DemRun::write_summary(long long moving, const observe::GlobalSample& global, long long migrations,
                           long long ghosts) {
  std::visit([&](auto& e) { write_summary_of(e, moving, global, migrations, ghosts); }, *engine);
}

template <class E>
void DemRun::write_summary_of(E& e, long long moving, const observe::GlobalSample& global, long long migrations,
                              long long ghosts) {
  const auto& st = e.state();
  double mean_temperature = 0.0;
  long counted = 0;
  for (const auto& r : rows)
    if (r.time >= c.output.average_start) {
      mean_temperature += r.global.granular_temperature;
      ++counted;
    }
  summary.string("engine", "dem");
  summary.integer("dimension", c.engine.dimension);
  summary.integer("particles", moving);
  summary.integer("fixed_particles", particle_count - moving);
  summary.string("case", c.path);
  summary.string("case_overrides", join_overrides(c.overrides));
  summary.string("version", kVersion);
  summary.string("contact_model", c.contact.model);
  summary.number("simulated_time", st.time);
  summary.number("wall_seconds", wall_seconds);
  summary.integer("steps", st.step);
  summary.number("time_step", st.time_step);
  summary.integer("threads", options.threads);
  summary.integer("mpi_ranks", comm.size());
  if (e.domain()) {  // the decomposition, and how much crossed it
    const auto& grid = e.domain()->grid();
    summary.string("mpi_grid", std::to_string(grid.shape[0]) + "x" + std::to_string(grid.shape[1]) + "x" +
                                   std::to_string(grid.shape[2]));
    summary.integer("mpi_migrations", migrations);
    summary.integer("mpi_ghosts", ghosts);
    summary.integer("mpi_rebalances", e.domain()->rebalances());
    summary.string("mpi_bounds", [&] {  // the final cuts along each cut axis
      std::string text;
      for (int a = 0; a < 3; ++a) {
        if (!grid.cut(a)) continue;
        text += std::string(text.empty() ? "" : "; ") + "xyz"[a] + ":";
        for (double b : grid.bounds[a]) text += " " + std::to_string(b);
      }
      return text;
    }());
  }
  summary.number("particle_steps_per_second",
                 wall_seconds > 0 ? moving * double(st.step - first_step) / wall_seconds : 0.0);
  if (restart) summary.string("restarted_from", options.restart);
  summary.number("max_overlap_over_diameter", max_overlap_seen);
  clog.report(summary, warnings);
  summary.number("kinetic_energy", global.kinetic_energy);
  summary.number("rotational_energy", global.rotational_energy);
  write_energy_budget(final_budget, final_budget_scale, summary);
  summary.number("granular_temperature", counted ? mean_temperature / counted : global.granular_temperature);
  // Lan's dimensionless groups (eqs. 4-1-2, 4-1-3) and Gamma, so sweeps can plot against them.
  summary.integer("gravity_axis", axis);
  summary.number("mass_holdup", derived.mass_holdup);
  summary.number("boundary_fluctuation_velocity", derived.boundary_fluctuation_velocity);
  summary.number("shaking_acceleration", derived.shaking_acceleration);
  // Long-term means over the rows after output.average_start, with blocked standard errors.
  const double from = c.output.average_start;
  // Lan's cell-average temperature (eq. 3-1-2) is the free particles' about their mean velocity.
  put(summary, "cell_temperature",
      series_mean(rows, from, [](const TimeseriesRow& r) { return r.global.granular_temperature; }));
  put(summary, "zone_temperature", series_mean(rows, from, [](const TimeseriesRow& r) { return r.zone_temperature; }));
  // Lan's T_x, T_y, T_z of Table 4.6: each component's share of the cell-average temperature,
  // <C_a^2> / 3, so that they add up to it (his T_x = T_z at Gamma = 5 and 20 are a third of <C_x^2>);
  // in 2D <C_a^2> / 2 of x and y.
  const int dim = c.engine.dimension;
  for (int a = 0; a < dim; ++a)
    put(summary, std::string("cell_temperature_") + "xyz"[a],
        series_mean(rows, from, [a, dim](const TimeseriesRow& r) { return r.global.component_temperature[a] / dim; }));
  if (floor_below && c.outlets.empty()) {  // a discharging silo's bulk fraction is its outlet's bed box's
    put(summary, "bed_height", series_mean(rows, from, [](const TimeseriesRow& r) { return r.bed.height; }));
    put(summary, "bulk_solids_fraction",
        series_mean(rows, from, [](const TimeseriesRow& r) { return r.bed.bulk_solids_fraction; }));
  }
  // Collisions per particle: contacts begun within the averaging window, per moving particle.
  const auto first =
      std::find_if(rows.begin(), rows.end(), [&](const TimeseriesRow& r) { return r.time >= from - 1e-12; });
  if (first != rows.end() && moving > 0 && rows.back().time > first->time) {
    const double span = rows.back().time - first->time;
    const double begun = 2.0 * static_cast<double>(rows.back().collisions - first->collisions);  // two partners each
    summary.number("collisions_per_particle", begun / moving);
    summary.number("collision_rate_per_particle", begun / moving / span);
    summary.number("wall_collision_rate_per_particle",
                   static_cast<double>(rows.back().wall_collisions - first->wall_collisions) / moving / span);
  }
  if (c.particles.init == "random") {
    // Radius expansion (section 2.2): how long it took, and the kinetic energy left when the radii
    // reached full size (the first row from then), which growth must not have pumped up.
    summary.number("expansion_time", derived.expansion_time);
    const auto grown = std::find_if(rows.begin(), rows.end(), [&](const TimeseriesRow& r) {
      return r.time >= derived.expansion_time * (1.0 - 1e-12);
    });
    if (grown != rows.end())
      summary.number("expansion_end_kinetic_energy", grown->global.kinetic_energy + grown->global.rotational_energy);
  }
  summary.integer("neighbor_rebuilds", e.statistics().rebuilds);
  if (c.servo.enabled) {
    summary.integer("servo_updates", e.servo().updates());
    summary.number("wall_gap", e.servo().state().gap);
    summary.number("cell_width", e.servo().state().width);
    put(summary, "mean_gap", series_mean(rows, from, [](const TimeseriesRow& r) { return r.servo.gap; }));
  }
  exit_status = finish_summary(summary, dir, errors, warnings, exit_status, options.echo_errors);
}

}  // namespace grainflow::run
