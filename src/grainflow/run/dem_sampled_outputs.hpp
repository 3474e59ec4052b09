// The sampled outputs of a DEM run besides the time series and profiles, each filled at its own
// interval from the run loop: trajectory.h5 ([trajectory]), zone_series.h5 ([zone_series]),
// convection fields ([field]) and tracer histories ([tracers]).
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/observe/trajectory_sampler.hpp"
#include "grainflow/observe/velocity_field.hpp"
#include "grainflow/observe/zone_profile.hpp"
#include "grainflow/parallel/communicator.hpp"

namespace grainflow::run {

// The floor (the wall on the low face along gravity) and the driven face's motion.
struct FloorMotion {
  double position = 0.0, velocity = 0.0;  // m, m/s along the axis; zero without a drive
};
template <class State>
FloorMotion floor_motion(const State& st, const CaseConfig& c) {
  FloorMotion m;
  for (const auto& wall : st.walls)
    if (c.drive.enabled && wall.face == c.drive.face) m = {wall.position, wall.velocity[wall.axis]};
  return m;
}
// Position of the floor along the gravity axis now: its wall if it has one, else domain.lo.
template <class State>
double floor_position(const State& st, const CaseConfig& c, int axis) {
  for (const auto& wall : st.walls)
    if (wall.face == 2 * axis) return wall.position;
  return c.domain.lo[axis];
}
// Phase of the floor's velocity cosine, omega (t - start) + phase, in [0, 2 pi); -1 without a
// drive along `axis` or before it starts.
double floor_phase(const CaseConfig& c, int axis, double time);

// On several MPI ranks every rank runs the outputs below over its own particles (the observers
// sum over the ranks where they must), and only rank 0 (`writes`) holds the files.

// trajectory.h5 and the sampler that fills it ([trajectory], Lan 1994 sections 3.2-3.3).
struct TrajectoryOutput {
  std::optional<io::H5Writer> file;  // rank 0's
  io::GrowingDataset time, velocity, position;
  std::optional<observe::TrajectorySampler> sampler;
  long requested = 0;

  // `p`: every particle of the run (the ids to follow come from it).
  TrajectoryOutput(const CaseConfig& c, const dem::DerivedQuantities& d, const ParticleStore& p, const std::string& dir,
                   bool writes, const observe::RankReduce& ranks);
  void finish(std::vector<std::string>& warnings);

  // Checkpoints: the sampler's state here, the file as it is in a copy beside the checkpoint.
  template <class Archive>
  void serialize(Archive& ar) {
    ar(*sampler);
  }
  void copy_stream(const std::string& path) {
    if (file) file->copy_to(path);
  }
  void resume_stream(const std::string& path) {
    if (file) io::resume_streams(path, {&time, &velocity, &position}, sampler->taken());
  }
};

// zone_series.h5: each zone's instantaneous mean velocity and the floor's motion at a fixed interval
// ([zone_series], Lan 1994 section 4.3), for spectra and floor cross-correlations.
struct ZoneSeriesOutput {
  std::optional<io::H5Writer> file;  // rank 0's
  io::GrowingDataset time, zone_velocity, floor_position, floor_velocity;
  double start = 0.0, interval = 0.0;
  long taken = 0, requested = 0, next = 0;  // next: index of the next sample time start + k interval

  ZoneSeriesOutput(const CaseConfig& c, const dem::DerivedQuantities& d, const observe::ZoneProfile& zones,
                   const std::string& dir, bool writes);
  // Samples at the first step at or after each start + k interval.
  template <class State>
  void observe(const State& st, observe::ZoneProfile& zones, const CaseConfig& c) {
    if (taken >= requested || st.time < start + next * interval - 0.5 * st.time_step) return;
    ++next;
    const FloorMotion floor = floor_motion(st, c);
    const auto u = zones.instantaneous_mean_velocity(st.particles);  // over every rank
    ++taken;
    if (!file) return;
    std::vector<double> row;
    row.reserve(3 * u.size());
    for (const Vec3& v : u) row.insert(row.end(), {v.x, v.y, v.z});
    time.append(&st.time);
    zone_velocity.append(row.data());
    floor_position.append(&floor.position);
    floor_velocity.append(&floor.velocity);
  }
  void finish(std::vector<std::string>& warnings);

  template <class Archive>
  void serialize(Archive& ar) {
    ar(taken, next);
  }
  void copy_stream(const std::string& path) {
    if (file) file->copy_to(path);
  }
  void resume_stream(const std::string& path) {
    if (file)
      io::resume_streams(path, {&time, &zone_velocity, &floor_position, &floor_velocity}, static_cast<std::size_t>(taken));
  }
};

// convection.csv / convection_phases.csv ([field], Lan 1994 Chapter 5).
struct FieldOutput {
  std::optional<observe::VelocityField> field;
  double start = 0.0, interval = 0.0;
  long next = 0;
  int axis = 1;  // gravity axis

  FieldOutput(const CaseConfig& c, const dem::DerivedQuantities& d, double vertical_lo);
  template <class State>
  void observe(const State& st, const CaseConfig& c) {
    if (st.time < start - 0.5 * st.time_step) return;
    if (interval > 0.0) {
      if (st.time < start + next * interval - 0.5 * st.time_step) return;
      ++next;
    }
    int bin = -1;
    if (field->bins() > 0) {
      const double phase = floor_phase(c, axis, st.time);
      if (phase >= 0.0) bin = std::min(field->bins() - 1, static_cast<int>(phase / (2.0 * M_PI) * field->bins()));
    }
    field->sample(st.particles, bin);
  }
  void write(const std::string& dir, const CaseConfig& c) const;

  template <class Archive>
  void serialize(Archive& ar) {
    if (field) ar(*field);  // made by the constructor from the case, as on the restart
    ar(next);
  }
};

// tracers.csv ([tracers], Lan 1994 section 5.2): rows of time, id, position (unwrapped), velocity,
// coordination (particles and walls touched) and the floor's motion; within a time, by id.
struct TracerOutput {
  std::vector<std::uint32_t> ids;  // sorted
  double start = 0.0, interval = 0.0;
  long next = 0;
  struct Row {
    long sample = 0;  // the sample's index: rows sort by it, then by id
    std::uint32_t id = 0;
    std::string text;
    template <class Archive>
    void serialize(Archive& ar) {
      ar(sample, id, text);
    }
  };
  std::vector<Row> rows;  // this rank's (MPI: the particles it owned at each sample)

  // `p`: every particle of the run (the species to follow are found in it).
  TracerOutput(const CaseConfig& c, const dem::DerivedQuantities& d, const ParticleStore& p);
  template <class Engine>
  void observe(const Engine& e, const CaseConfig& c) {
    const auto& st = e.state();
    if (st.time < start + next * interval - 0.5 * st.time_step) return;
    const FloorMotion floor = floor_motion(st, c);
    const auto& p = st.particles;
    const auto touch = e.coordination();
    const std::size_t first = rows.size();
    for (std::size_t i = 0; i < p.size(); ++i)  // particles are re-sorted: find them by id
      if (!p.ghost[i] && std::binary_search(ids.begin(), ids.end(), p.id[i]))
        rows.push_back({next, p.id[i],
                        row(st.time, p.id[i], e.unwrapped_position(i), p.velocity[i], touch[i].particles, touch[i].walls,
                            floor)});
    std::sort(rows.begin() + static_cast<std::ptrdiff_t>(first), rows.end(),
              [](const Row& a, const Row& b) { return a.id < b.id; });
    ++next;
  }
  // Collective on several ranks: rank 0 gathers every rank's rows and writes them in order.
  void write(const std::string& path, const parallel::Communicator& comm) const;
  // Collective: every rank's rows in order, on rank 0 (the others get none).
  std::vector<Row> gathered_rows(const parallel::Communicator& comm) const;

  template <class Archive>
  void serialize(Archive& ar) {
    ar(next, rows);
  }

 private:
  static std::string row(double time, std::uint32_t id, const Vec3& x, const Vec3& v, int particles, int walls,
                         const FloorMotion& floor);
};

}  // namespace grainflow::run
