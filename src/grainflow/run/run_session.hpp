// A run driven one piece at a time (the Python module's Simulation): built from a validated case,
// advanced by steps or simulated time, its particles read and changed between pieces, finished
// into its output folder. The pieces go through the same stages as `grainflow run`; run() is
// exactly that command's run, from wherever the pieces left it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/particles/particle_store.hpp"
#include "grainflow/run/run_options.hpp"

namespace grainflow::run {

class RunSession {
 public:
  virtual ~RunSession() = default;

  virtual bool event_driven() const = 0;
  virtual int dimension() const = 0;
  virtual double time() = 0;
  virtual long long steps() = 0;            // DEM steps so far; event-driven: events processed
  virtual double time_step() const = 0;     // s; 0 for the event-driven engine
  virtual double end_time() const = 0;      // the case's run.duration
  virtual long long last_step() const = 0;  // DEM: the step at run.duration; event-driven: 0

  // Both advance the run through its observers, records and snapshots as `grainflow run` would,
  // never beyond the case's end (InputError naming run.duration). They stop early on SIGINT or
  // SIGTERM (take_interrupt() then returns the signal; the run can go on), on a clogged outlet or a
  // collision budget, or on a failure: RunError, after the outputs (with the error) were written.
  virtual void advance_steps(long long n) = 0;  // DEM only
  virtual void advance_time(double dt) = 0;     // DEM: the nearest whole number of steps
  virtual int take_interrupt() = 0;

  // `grainflow run`: to the case's end (its final checkpoint included), then every output; the
  // exit status. finish(): the outputs now. Either once; afterwards the session only reads.
  virtual int run() = 0;
  virtual int finish() = 0;
  virtual bool finished() const = 0;

  // The engine's own particle arrays, every particle at time() (the event-driven engine brings
  // them there). Valid until the next advance, which may re-sort them.
  virtual ParticleStore& particles() = 0;
  // After velocities (any time) or positions (before the first advance only) were written into
  // particles(): the engine takes them up before it goes on (DEM: lists and forces at the new
  // positions; event-driven: every flight and event predicted anew).
  virtual void particles_written(bool positions) = 0;
  // DEM, between advances: particles of case species `species` (index) put in at `position` with
  // `velocity`, clear of every particle and wall (InputError naming the new particle otherwise;
  // in 2D on the discs' plane), taken into the run at the next step; their new ids. And particles
  // taken out by id at the next step (ids not present are ignored). The event-driven engine
  // refuses both (InputError).
  virtual std::vector<std::uint32_t> add_particles(const std::vector<int>& species, const std::vector<Vec3>& position,
                                                   const std::vector<Vec3>& velocity) = 0;
  virtual void remove_particles(const std::vector<std::uint32_t>& ids) = 0;
  virtual const std::string& output_directory() const = 0;
};

// The case's engine, with the records of `grainflow run` (run_records.hpp): resolved_case.toml
// now, run_log.json (naming `command_line`) when the run finishes. InputError as the run command's
// checks, before anything is written.
std::unique_ptr<RunSession> open_session(const CaseConfig& c, const RunOptions& options,
                                         const std::vector<std::string>& command_line);
// The engines' own, without the records.
std::unique_ptr<RunSession> open_dem_session(const CaseConfig& c, const RunOptions& options);
std::unique_ptr<RunSession> open_edmd_session(const CaseConfig& c, const RunOptions& options);

}  // namespace grainflow::run
