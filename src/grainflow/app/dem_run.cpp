#include "grainflow/app/dem_run.hpp"
#include "grainflow/app/run_support.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>
#include <unistd.h>

#include "grainflow/core/error.hpp"
#include "grainflow/core/version.hpp"
#include "grainflow/dem/contact_laws.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/io/vtu_writer.hpp"
#include "grainflow/observe/global_sample.hpp"
#include "grainflow/observe/trajectory_sampler.hpp"
#include "grainflow/observe/zone_profile.hpp"

namespace grainflow::app {
namespace {

struct TimeseriesRow {
  double time;
  observe::GlobalSample global;
  double floor_position, floor_velocity, max_overlap_ratio;
  long contacts, wall_contacts, rebuilds;
};

void write_timeseries(const std::string& path, const std::vector<TimeseriesRow>& rows) {
  io::write_atomically(path, [&](std::ostream& out) {
    out << "# units: time s, kinetic_energy J, rotational_energy J, granular_temperature m^2/s^2, "
           "mass_center_height m, floor_position m, floor_velocity m/s, max_overlap_over_diameter 1\n";
    out << "time,kinetic_energy,rotational_energy,granular_temperature,mass_center_height,floor_position,"
           "floor_velocity,max_overlap_over_diameter,contacts,wall_contacts,neighbor_rebuilds\n";
    for (const auto& r : rows)
      out << r.time << ',' << r.global.kinetic_energy << ',' << r.global.rotational_energy << ','
          << r.global.granular_temperature << ',' << r.global.mass_center_height << ',' << r.floor_position << ','
          << r.floor_velocity << ',' << r.max_overlap_ratio << ',' << r.contacts << ',' << r.wall_contacts << ','
          << r.rebuilds << '\n';
  });
}

void write_profiles(const std::string& path, const observe::ZoneProfile& profile, double diameter, double g) {
  io::write_atomically(path, [&](std::ostream& out) {
    out << "# zone profiles along the gravity axis, long-term averages over " << profile.samples()
        << " samples; temperature = about the instantaneous zone mean (Lan), temperature_time_mean = about the"
           " long-term zone mean (Campbell)\n";
    out << "# units: position m, Y 1 (position / d), velocities m/s, temperatures m^2/s^2, W 1 (sqrt(T/(g d))), "
           "kinetic_energy_density J/m^3\n";
    out << "zone,position_lo,position_hi,position,Y,solids_fraction,mean_velocity_x,mean_velocity_y,mean_velocity_z,"
           "temperature_x,temperature_y,temperature_z,temperature,temperature_time_mean,W,kinetic_energy_density\n";
    const auto zones = profile.averages();
    for (std::size_t z = 0; z < zones.size(); ++z) {
      const auto& a = zones[z];
      const double mid = 0.5 * (a.lo + a.hi);
      const double t = (a.temperature_lan.x + a.temperature_lan.y + a.temperature_lan.z) / 3.0;
      const double tm = (a.temperature_time_mean.x + a.temperature_time_mean.y + a.temperature_time_mean.z) / 3.0;
      out << z << ',' << a.lo << ',' << a.hi << ',' << mid << ',' << mid / diameter << ',' << a.solids_fraction << ','
          << a.mean_velocity.x << ',' << a.mean_velocity.y << ',' << a.mean_velocity.z << ',' << a.temperature_lan.x
          << ',' << a.temperature_lan.y << ',' << a.temperature_lan.z << ',' << t << ',' << tm << ','
          << (g > 0.0 ? std::sqrt(t / (g * diameter)) : 0.0) << ',' << a.kinetic_energy_density << '\n';
    }
  });
}

// The driven face's position and velocity along its axis (zero without a drive).
struct FloorMotion {
  double position = 0.0, velocity = 0.0;
};
template <class State>
FloorMotion floor_motion(const State& st, const CaseConfig& c) {
  FloorMotion m;
  for (const auto& wall : st.walls)
    if (c.drive.enabled && wall.face == c.drive.face) m = {wall.position, wall.velocity[wall.axis]};
  return m;
}

// Attributes every sampled HDF5 file of a DEM run carries, so it can be read without the case.
void write_run_attributes(io::H5Writer& file, const CaseConfig& c, const dem::DerivedQuantities& d, double start,
                          const std::string& units) {
  file.attribute("/", "start", start);
  file.attribute("/", "time_step", d.time_step);
  file.attribute("/", "diameter", d.reference_diameter);
  file.attribute("/", "gravity_axis", static_cast<std::int64_t>(d.gravity_axis));
  file.attribute("/", "case", c.path);
  file.attribute("/", "version", std::string(kVersion));
  file.attribute("/", "units", units);
}

// Commits a sampled file with the count taken (a shortened record is still valid data) and warns
// when the run ended before all requested samples.
void finish_samples(io::H5Writer& file, const std::string& table, long taken, long requested,
                    std::vector<std::string>& warnings) {
  file.attribute("/", "samples", static_cast<std::int64_t>(taken));
  if (taken < requested)
    warnings.push_back(table + ": the run ended after " + std::to_string(taken) + " of the " + std::to_string(requested) +
                       " requested samples (" + table + ".start and samples need a longer run.duration)");
  file.commit();
}

// trajectory.h5 and the sampler that fills it ([trajectory], Lan 1994 sections 3.2-3.3).
struct TrajectoryOutput {
  io::H5Writer file;
  io::GrowingDataset time, velocity, position;
  std::optional<observe::TrajectorySampler> sampler;
  long requested = 0;

  TrajectoryOutput(const CaseConfig& c, const dem::DerivedQuantities& d, const ParticleStore& p, const std::string& dir)
      : file(dir + "/trajectory.h5"), requested(c.trajectory.samples) {
    const auto& t = c.trajectory;
    std::vector<std::uint32_t> ids = t.particles;
    if (ids.empty())
      for (std::size_t i = 0; i < p.size(); ++i)
        if (p.motion[i] == Motion::free) ids.push_back(p.id[i]);
    std::sort(ids.begin(), ids.end());
    const double window = t.window > 0.0 ? t.window : 0.5 * c.run.collision_steps * d.time_step;
    const double start = t.start >= 0.0 ? t.start : c.output.average_start;
    std::vector<std::int64_t> id_column(ids.begin(), ids.end());
    file.write("/id", id_column);
    write_run_attributes(file, c, d, start, "time s, velocity m/s, position m (unwrapped), window and time_step s");
    file.attribute("/", "window", window);
    file.attribute("/", "samples_requested", static_cast<std::int64_t>(t.samples));
    file.attribute("/", "max_lag", static_cast<std::int64_t>(t.max_lag > 0 ? t.max_lag : t.samples / 2));
    file.attribute("/", "restitution", c.contact.restitution);
    const auto n = static_cast<unsigned long long>(ids.size());
    time = file.growing("/time", {}, 1024);
    velocity = file.growing("/velocity", {n, 3}, 16);
    position = file.growing("/position", {n, 3}, 16);
    sampler.emplace(std::move(ids), start, window, t.samples,
                    [this](double when, const std::vector<double>& v, const std::vector<double>& x) {
                      time.append(&when);
                      velocity.append(v.data());
                      position.append(x.data());
                    });
  }
  void finish(std::vector<std::string>& warnings) { finish_samples(file, "trajectory", sampler->taken(), requested, warnings); }
};

// zone_series.h5: each zone's instantaneous mean velocity and the floor's motion at a fixed interval
// ([zone_series], Lan 1994 section 4.3), for spectra and floor cross-correlations.
struct ZoneSeriesOutput {
  io::H5Writer file;
  io::GrowingDataset time, zone_velocity, floor_position, floor_velocity;
  double start = 0.0, interval = 0.0;
  long taken = 0, requested = 0, next = 0;  // next: index of the next sample time start + k interval

  ZoneSeriesOutput(const CaseConfig& c, const dem::DerivedQuantities& d, const observe::ZoneProfile& zones,
                   const std::string& dir)
      : file(dir + "/zone_series.h5"), requested(c.zone_series.samples) {
    const double f = c.drive.enabled ? c.drive.frequency[d.gravity_axis] : 0.0;
    interval = c.zone_series.interval > 0.0 ? c.zone_series.interval : 1.0 / (20.0 * f);
    start = c.zone_series.start >= 0.0 ? c.zone_series.start : c.output.average_start;
    const auto centres = zones.zone_centres();
    file.write("/zone_centre", centres, {centres.size()});
    write_run_attributes(file, c, d, start, "time s, zone_velocity m/s, floor_position m, floor_velocity m/s, zone_centre m");
    file.attribute("/", "interval", interval);
    file.attribute("/", "drive_frequency", f);
    time = file.growing("/time", {}, 1024);
    zone_velocity = file.growing("/zone_velocity", {centres.size(), 3}, 64);
    floor_position = file.growing("/floor_position", {}, 1024);
    floor_velocity = file.growing("/floor_velocity", {}, 1024);
  }
  // Samples at the first step at or after each start + k interval.
  template <class State>
  void observe(const State& st, observe::ZoneProfile& zones, const CaseConfig& c) {
    if (taken >= requested || st.time < start + next * interval - 0.5 * st.time_step) return;
    ++next;
    const FloorMotion floor = floor_motion(st, c);
    const auto u = zones.instantaneous_mean_velocity(st.particles);
    std::vector<double> row;
    row.reserve(3 * u.size());
    for (const Vec3& v : u) row.insert(row.end(), {v.x, v.y, v.z});
    time.append(&st.time);
    zone_velocity.append(row.data());
    floor_position.append(&floor.position);
    floor_velocity.append(&floor.velocity);
    ++taken;
  }
  void finish(std::vector<std::string>& warnings) { finish_samples(file, "zone_series", taken, requested, warnings); }
};

}  // namespace

int run_dem(const CaseConfig& c, const RunOptions& options) {
  namespace fs = std::filesystem;
  const dem::DerivedQuantities derived = dem::derive(c);
  dem::DemEngineVariant engine = dem::make_engine(c, dem::build_dem_state(c), options.threads);

  fs::create_directories(options.output_directory);
  const std::string dir = options.output_directory;
  std::optional<io::PvdSeries> snapshots;
  if (c.output.snapshot_interval > 0.0) snapshots.emplace(dir + "/snapshots");

  const int axis = derived.gravity_axis;
  double zone_thickness = c.output.zone_thickness > 0.0 ? c.output.zone_thickness : derived.reference_diameter;
  double area = 1.0;
  for (int a = 0; a < 3; ++a)
    if (a != axis) area *= c.domain.length(a);
  // Zones start at the floor's lowest reach, in whole zones below domain.lo, so that material under a
  // floor shaken below its rest position is still counted.
  double zones_lo = c.domain.lo[axis];
  if (c.drive.enabled && c.drive.face == axis * 2)
    zones_lo -= zone_thickness * std::ceil(c.drive.amplitude[axis] / zone_thickness - 1e-9);
  observe::ZoneProfile profile(axis, zones_lo, c.domain.hi[axis], zone_thickness, area);

  const double dt = derived.time_step;
  const long total_steps = static_cast<long>(std::llround(c.run.duration / dt));
  Schedule output_schedule(c.output.interval, dt);
  const double profile_interval = c.output.profile_interval > 0.0 ? c.output.profile_interval : c.output.interval / 10.0;
  Schedule profile_schedule(profile_interval, dt);
  Schedule snapshot_schedule(c.output.snapshot_interval, dt);
  const long average_from = static_cast<long>(std::ceil(c.output.average_start / dt - 1e-9));

  std::optional<TrajectoryOutput> trajectory;
  if (c.trajectory.enabled)
    std::visit([&](auto& e) { trajectory.emplace(c, derived, e.state().particles, dir); }, engine);

  std::optional<ZoneSeriesOutput> zone_series;
  if (c.zone_series.enabled) zone_series.emplace(c, derived, profile, dir);

  std::vector<TimeseriesRow> rows;
  std::vector<std::string> errors, warnings;
  Progress progress(!options.quiet && ::isatty(2), c.run.duration);
  const auto wall_start = std::chrono::steady_clock::now();
  auto last_flush = wall_start;
  double max_overlap_seen = 0.0;
  int exit_status = 0;

  auto record = [&](auto& e) {
    auto& st = e.state();
    TimeseriesRow row{};
    row.time = st.time;
    row.global = observe::sample_global(st.particles, axis);
    const FloorMotion floor = floor_motion(st, c);
    row.floor_position = floor.position;
    row.floor_velocity = floor.velocity;
    row.max_overlap_ratio = e.statistics().max_overlap_ratio;
    row.contacts = e.statistics().contacts;
    row.wall_contacts = e.statistics().wall_contacts;
    row.rebuilds = e.statistics().rebuilds;
    e.statistics().max_overlap_ratio = 0.0;
    rows.push_back(row);
    // Radius expansion (section 2.2) overlaps growing spheres on purpose: monitor only after it.
    const bool expanding = st.expansion_rate > 0.0;
    if (!expanding) max_overlap_seen = std::max(max_overlap_seen, row.max_overlap_ratio);
    if (!expanding && c.run.halt_overlap > 0.0 && row.max_overlap_ratio > c.run.halt_overlap) {
      std::ostringstream message;
      message << "maximum overlap / diameter " << row.max_overlap_ratio << " exceeded run.halt_overlap = "
              << c.run.halt_overlap << " before t = " << st.time << " s; increase the stiffness (k1 = " << derived.k1
              << " N/m) or lower the impact speeds";
      throw RunError(message.str());
    }
  };

  try {
    std::visit(
        [&](auto& e) {
          record(e);
          if (snapshots) snapshots->add(e.state().particles, e.state().time);
          for (long step = 1; step <= total_steps; ++step) {
            e.step();
            if (trajectory) trajectory->sampler->observe(e.state().particles, e.state().box, e.state().time - dt, e.state().time);
            if (zone_series) zone_series->observe(e.state(), profile, c);
            if (profile_schedule.due(step) && step >= average_from) profile.sample(e.state().particles);
            if (output_schedule.due(step)) {
              record(e);
              progress.update(e.state().time);
              const auto now = std::chrono::steady_clock::now();
              if (now - last_flush > std::chrono::seconds(30)) {
                write_timeseries(dir + "/timeseries.csv", rows);
                last_flush = now;
              }
            }
            if (snapshot_schedule.due(step) && snapshots) snapshots->add(e.state().particles, e.state().time);
          }
        },
        engine);
  } catch (const RunError& error) {
    errors.push_back(error.what());
    exit_status = 1;
  }
  progress.finish();
  if (trajectory) trajectory->finish(warnings);
  if (zone_series) zone_series->finish(warnings);
  const double wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  std::visit(
      [&](auto& e) {
        const auto& st = e.state();
        long moving = 0;
        for (std::size_t i = 0; i < st.particles.size(); ++i) moving += st.particles.motion[i] == Motion::free;
        const auto global = observe::sample_global(st.particles, axis);
        write_timeseries(dir + "/timeseries.csv", rows);
        write_profiles(dir + "/profiles.csv", profile, derived.reference_diameter, derived.gravity_magnitude);
        write_final_state(dir + "/final_state.csv", st.particles, st.species);

        double mean_temperature = 0.0;
        long counted = 0;
        for (const auto& r : rows)
          if (r.time >= c.output.average_start) {
            mean_temperature += r.global.granular_temperature;
            ++counted;
          }
        io::JsonObject summary;
        summary.string("engine", "dem");
        summary.integer("dimension", 3);
        summary.integer("particles", moving);
        summary.integer("fixed_particles", static_cast<long long>(st.particles.size()) - moving);
        summary.string("case", c.path);
        summary.string("version", kVersion);
        summary.string("contact_model", c.contact.model);
        summary.number("simulated_time", st.time);
        summary.number("wall_seconds", wall_seconds);
        summary.integer("steps", st.step);
        summary.number("time_step", st.time_step);
        summary.integer("threads", options.threads);
        summary.number("particle_steps_per_second", wall_seconds > 0 ? moving * double(st.step) / wall_seconds : 0.0);
        summary.number("max_overlap_over_diameter", max_overlap_seen);
        summary.number("kinetic_energy", global.kinetic_energy);
        summary.number("rotational_energy", global.rotational_energy);
        summary.number("granular_temperature", counted ? mean_temperature / counted : global.granular_temperature);
        summary.integer("profile_samples", profile.samples());
        summary.integer("neighbor_rebuilds", e.statistics().rebuilds);
        exit_status = finish_summary(summary, dir, errors, warnings, exit_status, options.echo_errors);
      },
      engine);
  return exit_status;
}

}  // namespace grainflow::app
