#include "grainflow/run/dem_sampled_outputs.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <tuple>

#include "grainflow/core/version.hpp"
#include "grainflow/io/atomic_file.hpp"

namespace grainflow::run {
namespace {

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

}  // namespace

double floor_phase(const CaseConfig& c, int axis, double time) {
  if (!c.drive.enabled || c.drive.face != 2 * axis || !(c.drive.frequency[axis] > 0.0) || time < c.drive.start) return -1.0;
  const double phase = 2.0 * M_PI * c.drive.frequency[axis] * (time - c.drive.start) + c.drive.phase[axis];
  return phase - 2.0 * M_PI * std::floor(phase / (2.0 * M_PI));
}

TrajectoryOutput::TrajectoryOutput(const CaseConfig& c, const dem::DerivedQuantities& d, const ParticleStore& p,
                                   const std::string& dir, bool writes, const observe::RankReduce& ranks)
    : requested(c.trajectory.samples) {
  const auto& t = c.trajectory;
  std::vector<std::uint32_t> ids = t.particles;
  if (ids.empty())
    for (std::size_t i = 0; i < p.size(); ++i)
      if (p.motion[i] == Motion::free) ids.push_back(p.id[i]);
  std::sort(ids.begin(), ids.end());
  const double window = t.window > 0.0 ? t.window : 0.5 * c.run.collision_steps * d.time_step;
  const double start = t.start >= 0.0 ? t.start : c.output.average_start;
  if (writes) {
    file.emplace(dir + "/trajectory.h5");
    std::vector<std::int64_t> id_column(ids.begin(), ids.end());
    file->write("/id", id_column);
    write_run_attributes(*file, c, d, start, "time s, velocity m/s, position m (unwrapped), window and time_step s");
    file->attribute("/", "window", window);
    file->attribute("/", "samples_requested", static_cast<std::int64_t>(t.samples));
    file->attribute("/", "max_lag", static_cast<std::int64_t>(t.max_lag > 0 ? t.max_lag : t.samples / 2));
    file->attribute("/", "restitution", d.restitution);  // the binary contact's, for Savage–Dai's D
    const auto n = static_cast<unsigned long long>(ids.size());
    time = file->growing("/time", {}, 1024);
    velocity = file->growing("/velocity", {n, 3}, 16);
    position = file->growing("/position", {n, 3}, 16);
  }
  sampler.emplace(std::move(ids), start, window, t.samples,
                  [this](double when, const std::vector<double>& v, const std::vector<double>& x) {
                    if (!file) return;
                    time.append(&when);
                    velocity.append(v.data());
                    position.append(x.data());
                  });
  sampler->set_reduce(ranks);
}

void TrajectoryOutput::finish(std::vector<std::string>& warnings) {
  if (file) finish_samples(*file, "trajectory", sampler->taken(), requested, warnings);
}

ZoneSeriesOutput::ZoneSeriesOutput(const CaseConfig& c, const dem::DerivedQuantities& d,
                                   const observe::ZoneProfile& zones, const std::string& dir, bool writes)
    : requested(c.zone_series.samples) {
  const double f = c.drive.enabled ? c.drive.frequency[d.gravity_axis] : 0.0;
  interval = c.zone_series.interval > 0.0 ? c.zone_series.interval : 1.0 / (20.0 * f);
  start = c.zone_series.start >= 0.0 ? c.zone_series.start : c.output.average_start;
  if (!writes) return;
  file.emplace(dir + "/zone_series.h5");
  const auto centres = zones.zone_centres();
  file->write("/zone_centre", centres, {centres.size()});
  write_run_attributes(*file, c, d, start, "time s, zone_velocity m/s, floor_position m, floor_velocity m/s, zone_centre m");
  file->attribute("/", "interval", interval);
  file->attribute("/", "drive_frequency", f);
  time = file->growing("/time", {}, 1024);
  zone_velocity = file->growing("/zone_velocity", {centres.size(), 3}, 64);
  floor_position = file->growing("/floor_position", {}, 1024);
  floor_velocity = file->growing("/floor_velocity", {}, 1024);
}

void ZoneSeriesOutput::finish(std::vector<std::string>& warnings) {
  if (file) finish_samples(*file, "zone_series", taken, requested, warnings);
}

FieldOutput::FieldOutput(const CaseConfig& c, const dem::DerivedQuantities& d, double vertical_lo) : axis(d.gravity_axis) {
  const auto& f = c.field;
  const double cell = f.cell > 0.0 ? f.cell : d.reference_diameter;
  start = f.start >= 0.0 ? f.start : c.output.average_start;
  interval = f.interval;
  field.emplace(f.axis, axis, c.domain.lo[f.axis], c.domain.hi[f.axis], vertical_lo, c.domain.hi[axis], cell, f.phase_bins);
}

void FieldOutput::write(const std::string& dir, const CaseConfig& c) const {
  const char* names = "xyz";
  const double cell = c.field.cell > 0.0 ? c.field.cell : field->cell();
  auto header = [&](std::ostream& out, const std::string& what) {
    out << "# " << what << ": horizontal axis " << names[c.field.axis] << ", vertical axis " << names[axis]
        << ", cell " << cell << " m, " << field->samples()
        << " samples; a particle's velocity counts toward the cell holding its centre (Lan 1994 Fig. 5.1)\n";
    out << "# units: horizontal, vertical m (cell centres), velocities m/s; visits = particle centres counted\n";
  };
  auto cells = [&](std::ostream& out, int bin) {
    for (const auto& k : field->cells(bin)) {
      if (bin >= 0) out << bin << ',';
      out << k.column << ',' << k.row << ',' << k.horizontal << ',' << k.vertical << ',' << k.visits << ','
          << k.velocity_horizontal << ',' << k.velocity_vertical << ',' << k.speed() << '\n';
    }
  };
  io::write_atomically(dir + "/convection.csv", [&](std::ostream& out) {
    header(out, "long-term convection field");
    out << "column,row,horizontal,vertical,visits,velocity_horizontal,velocity_vertical,speed\n";
    cells(out, -1);
  });
  if (field->bins() == 0) return;
  io::write_atomically(dir + "/convection_phases.csv", [&](std::ostream& out) {
    header(out, "convection field in " + std::to_string(field->bins()) +
                    " bins of the floor phase omega (t - drive.start) + phase (0: floor at rest height moving up fastest)");
    out << "phase_bin,column,row,horizontal,vertical,visits,velocity_horizontal,velocity_vertical,speed\n";
    for (int b = 0; b < field->bins(); ++b) cells(out, b);
  });
}

TracerOutput::TracerOutput(const CaseConfig& c, const dem::DerivedQuantities& d, const ParticleStore& p) {
  const auto& t = c.tracers;
  ids = t.particles;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (const auto& name : t.species)
      if (p.species[i] >= 0 && static_cast<std::size_t>(p.species[i]) < c.species.size() &&
          c.species[p.species[i]].name == name)
        ids.push_back(p.id[i]);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  start = t.start;
  const double f = c.drive.enabled ? c.drive.frequency[d.gravity_axis] : 0.0;
  interval = t.interval > 0.0 ? t.interval : f > 0.0 ? 1.0 / (20.0 * f) : c.output.interval;
}

std::string TracerOutput::row(double time, std::uint32_t id, const Vec3& x, const Vec3& v, int particles, int walls,
                              const FloorMotion& floor) {
  char line[400];
  std::snprintf(line, sizeof line, "%.10g,%u,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%d,%d,%.10g,%.10g\n", time, id, x.x,
                x.y, x.z, v.x, v.y, v.z, particles, walls, floor.position, floor.velocity);
  return line;
}

std::vector<TracerOutput::Row> TracerOutput::gathered_rows(const parallel::Communicator& comm) const {
  std::vector<Row> all;
  if (comm.size() == 1) {
    all = rows;
  } else {
    // Each row as sample, id, length and text; rank 0 merges them by sample, then id.
    std::vector<std::uint8_t> mine;
    auto put = [&mine](const void* data, std::size_t size) {
      const auto* bytes = static_cast<const std::uint8_t*>(data);
      mine.insert(mine.end(), bytes, bytes + size);
    };
    for (const Row& r : rows) {
      const std::uint64_t length = r.text.size();
      put(&r.sample, sizeof r.sample);
      put(&r.id, sizeof r.id);
      put(&length, sizeof length);
      put(r.text.data(), r.text.size());
    }
    for (const auto& from : comm.gather(mine)) {
      std::size_t at = 0;
      auto take = [&](void* data, std::size_t size) {
        std::memcpy(data, from.data() + at, size);
        at += size;
      };
      while (at < from.size()) {
        Row r;
        std::uint64_t length = 0;
        take(&r.sample, sizeof r.sample);
        take(&r.id, sizeof r.id);
        take(&length, sizeof length);
        r.text.assign(reinterpret_cast<const char*>(from.data() + at), length);
        at += length;
        all.push_back(std::move(r));
      }
    }
    std::sort(all.begin(), all.end(), [](const Row& a, const Row& b) { return std::tie(a.sample, a.id) < std::tie(b.sample, b.id); });
  }
  return all;
}

void TracerOutput::write(const std::string& path, const parallel::Communicator& comm) const {
  const std::vector<Row> all = gathered_rows(comm);
  if (!comm.root()) return;
  io::write_atomically(path, [&](std::ostream& out) {
    out << "# tracer histories: unwrapped centre, velocity, coordination (particles touched) and walls touched, with "
           "the floor's motion\n";
    out << "# units: time s, x y z m, vx vy vz m/s, floor_position m, floor_velocity m/s\n";
    out << "time,id,x,y,z,vx,vy,vz,coordination,wall_contacts,floor_position,floor_velocity\n";
    for (const auto& r : all) out << r.text;
  });
}

}  // namespace grainflow::run
