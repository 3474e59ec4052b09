#include "grainflow/run/dem_timeseries.hpp"

#include "grainflow/io/atomic_file.hpp"

namespace grainflow::run {

void write_timeseries(const std::string& path, const std::vector<TimeseriesRow>& rows, bool servo) {
  io::write_atomically(path, [&](std::ostream& out) {
    out << "# units: time s, kinetic_energy J, rotational_energy J, granular_temperature m^2/s^2 (about the whole "
           "bed's "
           "mean velocity), mass_center_height m, floor_position m, floor_velocity m/s, max_overlap_over_diameter 1, "
           "bed_height m (above the floor), bulk_solids_fraction 1, cell_temperature m^2/s^2 (Lan's cell average: "
           "about "
           "the whole cell's mean velocity, eq. 3-1-2), zone_temperature m^2/s^2 (about each zone's instantaneous "
           "mean, "
           "eq. 3-1-9, mass-weighted over the bed), collisions and wall_collisions: contacts begun since the start; "
           "energy budget since the "
           "start: energy_input (gravity along periodic axes, walls and their bumps, boundaries: sliding images, "
           "growth), energy_change (kinetic + rotational + "
           "potential + elastic), energy_dissipated J, energy_budget_residual (input - change - dissipated) / "
           "max(|input|, |dissipated|)\n";
    if (servo)
      out << "# servo: gap m, wall_speed m/s (> 0 opening), wall_stress as pressure (the last update's), top_speed "
             "m/s\n";
    out << "time,kinetic_energy,rotational_energy,granular_temperature,mass_center_height,floor_position,"
           "floor_velocity,max_overlap_over_diameter,contacts,wall_contacts,neighbor_rebuilds,bed_height,"
           "bulk_solids_fraction,ballistic_particles,cell_temperature,zone_temperature,collisions,wall_collisions,"
           "energy_input,"
           "energy_change,energy_dissipated,energy_budget_residual"
        << (servo ? ",gap,wall_speed,wall_stress,top_speed" : "") << "\n";
    for (const auto& r : rows) {
      out << r.time << ',' << r.global.kinetic_energy << ',' << r.global.rotational_energy << ','
          << r.global.granular_temperature << ',' << r.global.mass_center_height << ',' << r.floor_position << ','
          << r.floor_velocity << ',' << r.max_overlap_ratio << ',' << r.contacts << ',' << r.wall_contacts << ','
          << r.rebuilds << ',' << r.bed.height << ',' << r.bed.bulk_solids_fraction << ',' << r.bed.ballistic << ','
          << r.global.granular_temperature << ',' << r.zone_temperature << ',' << r.collisions << ','
          << r.wall_collisions << ',' << r.budget.input() << ',' << r.budget.change << ',' << r.budget.dissipated << ','
          << r.budget_residual;
      if (servo)
        out << ',' << r.servo.gap << ',' << r.servo.wall_speed << ',' << r.servo.measured_stress << ','
            << r.servo.top_speed;
      out << '\n';
    }
  });
}

void put(io::JsonObject& summary, const std::string& key, const MeanWithError& m) {
  summary.number(key, m.mean);
  if (std::isfinite(m.error)) summary.number(key + "_error", m.error);
}

}  // namespace grainflow::run
