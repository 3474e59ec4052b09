#include "grainflow/run/dem_run.hpp"
#include "grainflow/run/dem_run_stages.hpp"
#include "grainflow/run/run_session_over.hpp"
#include "grainflow/run/clog_watch.hpp"
#include "grainflow/run/run_support.hpp"
#include "grainflow/run/checkpointing.hpp"
#include "grainflow/run/interrupt.hpp"
#include "grainflow/run/dem_parallel_view.hpp"
#include "grainflow/run/dem_portable_state.hpp"
#include "grainflow/run/dem_timeseries.hpp"
#include "grainflow/run/dem_wall_outputs.hpp"
#include "grainflow/parallel/communicator.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <unistd.h>

#include "grainflow/core/error.hpp"
#include "grainflow/core/version.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/dem/fault_checks.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/analysis/block_average.hpp"
#include "grainflow/run/observer_registry.hpp"
#include "grainflow/io/vtu_writer.hpp"
#include "grainflow/observe/bed_surface.hpp"
#include "grainflow/observe/global_sample.hpp"
#include "grainflow/observe/floor_motion.hpp"
#include "grainflow/observe/zone_profile_observer.hpp"

namespace grainflow::run {
namespace {

// What observers see of a state; the clock is refreshed before each use.
observe::Frame frame_of(const dem::DemState& st) {
  observe::Frame f;
  f.dimension = st.dimension;
  f.time = st.time;
  f.time_step = st.time_step;
  f.step = st.step;
  f.particles = &st.particles;
  f.box = &st.box;
  f.walls = FaceWalls(st.walls);
  return f;
}

}  // namespace

DemRun::DemRun(const CaseConfig& case_config, const RunOptions& run_options)
    : c(case_config),
      options(run_options),
      derived(dem::derive(case_config)),
      dt(derived.time_step),
      output_schedule(c.output.interval, dt),
      snapshot_schedule(c.output.snapshot_interval, dt),
      checkpoint_schedule(c.output.checkpoint_interval, dt) {
  namespace fs = std::filesystem;
  dem::DemState initial = dem::build_dem_state(c);
  particle_count = static_cast<long long>(initial.particles.size());
  if (!options.restart.empty()) restart = read_restart(options.restart, c, particle_count, comm);
  if (restart && restart->portable && c.servo.enabled)  // the portable state has no walls' servo state
    throw InputError(c.path, "servo",
                     "a run with pressure-controlled walls restarts on as many MPI ranks as wrote " + options.restart +
                         " (" + std::to_string(restart->header.ranks) + ")");
  if (restart && restart->portable) {
    portable_restart.emplace(io::StateArchive::for_reading(restart->state, options.restart));
    portable_restart->tag("portable dem run with observers");
    read_portable_particles(*portable_restart, portable_particles, initial);
  }

  // Refused before anything is written.
  if (ranks && c.lees_edwards_rate != 0.0)
    throw InputError(c.path, "lees_edwards", "runs on one MPI rank for now (threads are fine): run it without mpirun");
  clog = ClogWatch(c, derived.max_diameter);
  if (ranks && !c.insertions.empty())
    throw InputError(c.path, "insertion",
                     "runs on one MPI rank for now (threads are fine): every rank would place the same particles");
  fs::create_directories(options.output_directory);
  dir = options.output_directory;
  if (c.output.snapshot_interval > 0.0) snapshots.emplace(dir + "/snapshots");
  if (snapshots && !c.geometry.empty()) {
    wall_snapshots.emplace(dir + "/snapshots", initial.walls);
    snapshots->set_parts(wall_snapshots->parts());
  }

  axis = derived.gravity_axis;
  total_steps = static_cast<long>(std::llround(c.run.duration / dt));

  context =
      observe::RunContext{&c,     c.engine.dimension, axis, derived.reference_diameter, dt, derived.restitution, dir,
                          writes, rank_reduce,        &comm};
  const observe::ZoneLayout zones(context);
  area = zones.area;
  zones_now.emplace(zones.profile(context));
  frame = frame_of(initial);  // every particle, before the decomposition; bound to the engine in start()
  observers = make_observers(EngineKind::dem, context, frame);
  sink = observe::OutputSink{dir, writes, &summary, &warnings};

  if (ranks) domain = dem::EngineDomain{&comm, dem_grid(initial, comm.size())};
  engine.reset(
      new dem::DemEngineVariant(dem::make_engine(c, std::move(initial), options.threads, domain ? &*domain : nullptr)));

  bed_thresholds = observe::BedSurfaceThresholds{c.output.bed_gap_fraction, c.output.bed_surface_fraction};
  floor_below = c.gravity[axis] < 0.0;
  progress.emplace(!options.quiet && ::isatty(2) && writes, c.run.duration);
  wall_start = std::chrono::steady_clock::now();
  last_flush = wall_start;
}

void DemRun::snapshot(const dem::DemState& st) {
  if (wall_snapshots && writes) wall_snapshots->write(st.walls, st.box, snapshots->size());
  if (ranks) snapshots->add_piece(st.particles, st.time, comm.rank(), comm.size());
  else snapshots->add(st.particles, st.time);
}

// The frame observers see: pointers into the engine's state (built in place, so they stay valid).
template <class E>
void DemRun::bind_frame(E& e) {
  frame = frame_of(e.state());
  frame.coordination = [&e] { return e.coordination(); };
  frame.contact_forces = [&e](const observe::Frame::ContactForceVisit& visit) { e.for_each_contact_force(visit); };
  frame.geometry_loads = [&e] { return geometry_loads(e); };
  frame.outlet_counts = [&e] { return outlet_tallies(e); };
}

template <class E>
const observe::Frame& DemRun::frame_now(E& e) {
  const auto& st = e.state();
  frame.time = st.time;
  frame.step = st.step;
  frame.collisions = e.statistics().collisions;
  return frame;
}

// All particles on rank 0 (for final_state.csv and a checkpoint's datasets); the engine's own on
// one rank.
template <class E>
const ParticleStore& DemRun::all_particles(E& e) {
  if (!ranks) return e.state().particles;
  gathered = gather_particles(e.state().particles, comm);
  return gathered;
}

// The run's whole state, one function for both directions (checkpoint and restart).
template <class E>
void DemRun::transfer(io::StateArchive& ar, E& e) {
  ar.tag("dem run with observers");
  ar(e, rows, max_overlap_seen, output_schedule, snapshot_schedule, checkpoint_schedule);
  if (snapshots) ar(*snapshots);
  for (auto& o : observers) {
    ar.tag(o->name());
    o->serialize(ar);
  }
  ar.tag("end of dem run");
}

// The same in a form no decomposition shapes, for a restart on another rank count: the engine's
// state gathered by ids, the accumulators each rank holds a share of summed over the ranks (to be
// kept by one rank at the restart). Collective; rank 0's archive is the one written.
template <class E>
void DemRun::portable_run(io::StateArchive& ar, E& e) {
  ar.tag("portable dem run with observers");
  write_portable_engine(ar, e, comm);
  ar(rows, max_overlap_seen, output_schedule, snapshot_schedule, checkpoint_schedule);
  if (snapshots) ar(*snapshots);
  for (auto& o : observers) {
    ar.tag(o->name());
    o->save_portable(ar);
  }
  ar.tag("end of portable dem run");
}

template <class E>
void DemRun::restore_portable_run(io::StateArchive& ar, E& e) {
  read_portable_contacts(ar, e, portable_particles, writes);
  ar(rows, max_overlap_seen, output_schedule, snapshot_schedule, checkpoint_schedule);
  if (snapshots) ar(*snapshots);
  // Rank 0 keeps the summed accumulators; the other ranks add their shares from here on.
  for (auto& o : observers) {
    ar.tag(o->name());
    o->load_portable(ar, writes);
  }
  ar.tag("end of portable dem run");
  ar.expect_end();
}

// The HDF5 streams are copied beside the checkpoint first: a checkpoint never counts more samples
// than its copies hold. Several MPI ranks: each rank's own state, gathered by rank 0 into the one
// file, and the portable state.
template <class E>
void DemRun::checkpoint(E& e) {
  for (auto& o : observers) o->save_streams(dir);
  io::StateArchive portable = io::StateArchive::for_writing();
  portable_run(portable, e);
  write_run_checkpoint(
      dir, c, all_particles(e), e.state().time, e.state().step, [&](io::StateArchive& ar) { transfer(ar, e); }, comm,
      portable.bytes());
  gathered = ParticleStore{};
}

// One time-series row; the faults and the overlap halt stop the run here, on every rank at once.
template <class E>
void DemRun::record(E& e) {
  std::string fault;
  try {
    dem::check_faults(e.state(), derived);
  } catch (const RunError& error) {
    fault = error.what();
  }
  if (ranks) fault = fault_on_any_rank(fault, comm);
  if (!fault.empty()) {
    stopped_together = true;
    throw RunError(fault);
  }
  // Each rank measures its own particles; the sums are added over the ranks.
  const auto& st = e.state();
  const dem::ContactStatistics stats = ranks ? global_statistics(e.statistics(), comm) : e.statistics();
  TimeseriesRow row{};
  row.time = st.time;
  row.global = observe::sample_global(st.particles, axis, st.dimension, rank_reduce);
  const observe::FloorMotion floor = observe::floor_motion(frame.walls, c);
  row.floor_position = floor.position;
  row.floor_velocity = floor.velocity;
  row.max_overlap_ratio = stats.max_overlap_ratio;
  row.contacts = stats.contacts;
  row.wall_contacts = stats.wall_contacts;
  row.rebuilds = stats.rebuilds;
  row.collisions = stats.collisions;
  row.wall_collisions = stats.wall_collisions;
  if (floor_below)
    row.bed =
        observe::measure_bed_surface(st.particles, st.dimension, axis, observe::floor_position(frame.walls, c, axis),
                                     area, derived.reference_diameter, bed_thresholds, rank_reduce);
  row.zone_temperature = zones_now->instantaneous_temperature(st.particles);
  const auto [budget, start_energy] = global_energy_budget(e);
  row.budget = budget;
  row.budget_residual = budget.residual(start_energy);
  row.servo = e.servo().state();
  e.statistics().max_overlap_ratio = 0.0;
  rows.push_back(row);
  if (clog.on()) {  // the particles out so far, over the ranks
    double out = 0.0;
    for (const auto& tally : outlet_tallies(e)) out += static_cast<double>(tally.removed);
    clog.update(ranks ? comm.sum(out) : out, st.time);
  }
  // Radius expansion (section 2.2) overlaps growing spheres on purpose: monitor only after it.
  // The settling before a drive starts is not monitored either: Lan's 1% criterion calibrates K1
  // for the shaken bed, and grains poured from a height land harder than the floor drives them.
  const bool expanding = st.expansion_rate > 0.0;
  const bool settling = c.drive.enabled && c.drive.start > 0.0 && st.time <= c.drive.start;
  const bool monitored = !expanding && !settling;
  if (monitored) max_overlap_seen = std::max(max_overlap_seen, row.max_overlap_ratio);
  if (monitored && c.run.halt_overlap > 0.0 && row.max_overlap_ratio > c.run.halt_overlap) {
    stopped_together = true;  // the overlap is the maximum over all ranks: each stops here
    throw RunError(dem::overlap_halt_message(e.state(), e.pairs(), derived, row.max_overlap_ratio, c.run.halt_overlap));
  }
}

// A fresh start records t = 0; a restart reads its state back (this rank count's, or portable).
template <class E>
void DemRun::start(E& e) {
  bind_frame(e);
  if (portable_restart) {
    restore_portable_run(*portable_restart, e);
    warnings.push_back("continued on " + std::to_string(comm.size()) + " MPI rank(s) from a checkpoint of " +
                       std::to_string(restart->header.ranks) +
                       ": the same state and physics, but not the same bits as a run that never stopped "
                       "(the neighbour lists were built afresh, so forces add up in another order)");
  } else if (restart) {
    restore_run_state(*restart, options.restart, [&](io::StateArchive& ar) { transfer(ar, e); });
  }
  if (restart) {
    const std::string beside = checkpoint_folder(options.restart);
    for (auto& o : observers) o->resume_streams(beside);
    first_step = e.state().step;
  } else {
    record(e);
    for (auto& o : observers) o->sample_start(frame_now(e));
    if (snapshots) snapshot(e.state());
  }
}

template <class E>
void DemRun::step_loop(E& e, long last) {
  for (long step = e.state().step + 1; step <= last; ++step) {
    // Under MPI the ranks agree every 100 steps, so that all stop at the same step.
    if (!ranks) interrupted = pending_interrupt();
    else if (step % 100 == 0) interrupted = static_cast<int>(comm.max(pending_interrupt()));
    if (interrupted != 0) break;
    e.step();
    // The schedules are the same on every rank, so all refresh together.
    if (ranks && std::any_of(observers.begin(), observers.end(),
                             [&](const auto& o) { return o->reads_contact_forces_at(step); }))
      e.refresh_ghosts();
    const observe::Frame& now = frame_now(e);
    for (auto& o : observers) o->sample(now);
    if (output_schedule.due(step)) {
      record(e);
      if (clog.clogged()) break;
      progress->update(e.state().time);
      // Every 30 s of wall time the files so far are written (decided together: tracers gather).
      const auto now = std::chrono::steady_clock::now();
      if (comm.any(now - last_flush > std::chrono::seconds(30))) {
        if (writes) write_timeseries(dir + "/timeseries.csv", rows, c.servo.enabled);
        for (auto& o : observers) o->flush(sink);
        last_flush = now;
      }
    }
    if (snapshot_schedule.due(step)) snapshot(e.state());
    if (checkpoint_schedule.due(step) && step < total_steps) checkpoint(e);
  }
}

// A fault seen on one rank inside a step cannot reach the others, which wait in the next exchange:
// stop all. An interruption becomes the run's error and exit status 128 + signal.
void DemRun::handle_failure_outside_loop() {
  if (ranks && exit_status != 0 && !stopped_together) {
    std::cerr << "grainflow: rank " << comm.rank() << ": run failed: " << errors.back()
              << " (found inside a step on one rank, so every rank stops without writing the outputs)\n";
    comm.abort(1);
  }
  if (interrupted != 0) {
    const double t = std::visit([](auto& e) { return e.state().time; }, *engine);
    errors.push_back(interrupted_message(interrupted, t, " s", c, dir));
    exit_status = 128 + interrupted;
  }
}

// A failure found in a stage becomes the run's error (summary.json, exit status 1).
void DemRun::catch_failures(const std::function<void()>& stage) {
  try {
    stage();
  } catch (const dem::NonFiniteState& fault) {  // found by the engine, which does not know the case
    std::string message = dem::with_cause(fault, derived);
    if (ranks) {  // every rank threw at the same rebuild: rank 0 reports the faulty rank's message
      const bool mine = std::string(fault.what()) != dem::kFaultOnAnotherRank;
      message = fault_on_any_rank(mine ? message : "", comm);
      stopped_together = true;
    }
    errors.push_back(message);
    exit_status = 1;
  } catch (const RunError& error) {
    errors.push_back(error.what());
    exit_status = 1;
  }
}

void DemRun::begin() {
  if (begun) return;
  begun = true;
  catch_failures([&] { std::visit([&](auto& e) { start(e); }, *engine); });
}

bool DemRun::advance(long last) {
  begin();
  if (exit_status == 0)
    catch_failures([&] { std::visit([&](auto& e) { step_loop(e, std::min(last, total_steps)); }, *engine); });
  return exit_status != 0;
}

int DemRun::finish() {
  if (done) return exit_status;
  done = true;
  begin();
  handle_failure_outside_loop();
  progress->finish();
  for (auto& o : observers) o->finish(sink);
  wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::visit([&](auto& e) { write_outputs(e); }, *engine);
  return exit_status;
}

int DemRun::run() {
  advance(total_steps);
  // The end, or an interruption: a checkpoint to continue from (the end's, to run longer).
  if (exit_status == 0 && (interrupted != 0 || c.output.checkpoint_interval > 0.0))
    catch_failures([&] { std::visit([&](auto& e) { checkpoint(e); }, *engine); });
  return finish();
}

// The ranks' shares of the energy budget summed (collective), and the starting energy.
template <class E>
std::pair<engine_api::EnergyBudget, double> DemRun::global_energy_budget(const E& e) const {
  engine_api::EnergyBudget b = e.energy_budget();
  double* parts[] = {&b.gravity_work,    &b.wall_work, &b.boundary_work, &b.growth_work,
                     &b.separation_work, &b.change,    &b.dissipated};
  double sums[std::size(parts) + 1];
  for (std::size_t k = 0; k < std::size(parts); ++k) sums[k] = *parts[k];
  sums[std::size(parts)] = e.energy_tally().start_energy;
  rank_reduce.sum(sums, std::size(sums));
  for (std::size_t k = 0; k < std::size(parts); ++k) *parts[k] = sums[k];
  return {b, sums[std::size(parts)]};
}

template <class E>
void DemRun::write_outputs(E& e) {
  const auto& st = e.state();
  const ParticleStore& everyone = all_particles(e);  // rank 0: every rank's, for final_state.csv
  long long moving = 0;
  for (std::size_t i = 0; i < st.particles.size(); ++i) moving += st.particles.counted(i);
  moving = ranks ? comm.sum(moving) : moving;
  const auto global = observe::sample_global(st.particles, axis, st.dimension, rank_reduce);
  const long long migrations = e.domain() ? comm.sum(e.domain()->migrated()) : 0;
  const long long ghosts = e.domain() ? comm.sum(e.domain()->ghosts()) : 0;
  const observe::Frame& last = frame_now(e);
  const auto [budget, start_energy] = global_energy_budget(e);
  final_budget = budget;
  final_budget_scale = start_energy;
  for (auto& o : observers) o->write(last, sink);  // collective: rank 0 writes
  if (!writes) return;                             // rank 0 writes the run's other files
  write_timeseries(dir + "/timeseries.csv", rows, c.servo.enabled);
  write_final_state(dir + "/final_state.csv", everyone, st.species);
  write_summary(moving, global, migrations, ghosts);
}

namespace {

// A RunSession over a DemRun: advanced by whole steps.
class DemSession final : public RunSessionOver<DemRun> {
 public:
  using RunSessionOver::RunSessionOver;
  bool event_driven() const override { return false; }
  long long steps() override { return std::visit([](auto& e) { return e.state().step; }, run_.engine_variant()); }
  double time_step() const override { return run_.time_step(); }
  long long last_step() const override { return run_.last_step(); }
  void advance_steps(long long n) override {
    refuse_when_finished();
    refuse_negative(static_cast<double>(n), "steps");
    const long long target = steps() + n;
    refuse_beyond(target > last_step(), "step " + std::to_string(last_step()) + " (time " + std::to_string(end_time()) + ")",
                  "step " + std::to_string(target));
    advance_driver(static_cast<long>(target));
  }
  void advance_time(double dt) override {
    refuse_negative(dt, "a time");
    advance_steps(std::llround(dt / time_step()));
  }
  void particles_written(bool positions) override {
    if (steps() > 0 && positions)
      throw InputError(case_.path, "", "positions are written before the first step only (the contacts remember them)");
    written_ = written_ || steps() == 0;  // velocities later need nothing: the next kick starts from them
  }
  std::vector<std::uint32_t> add_particles(const std::vector<int>& species, const std::vector<Vec3>& position,
                                           const std::vector<Vec3>& velocity) override {
    std::vector<ParticleStore::Record> records;
    for (std::size_t k = 0; k < position.size(); ++k) {
      const int s = species[k];
      if (s < 0 || s >= static_cast<int>(case_.species.size()))
        throw InputError(case_.path, "species", "the new particle " + std::to_string(k) + " names species " +
                                                    std::to_string(s) + ": the case has " +
                                                    std::to_string(case_.species.size()));
      if (case_.species[s].frozen)
        throw InputError(case_.path, "species", "'" + case_.species[s].name + "' is frozen: the case places those");
      const ParticleStore::Record r = dem::species_particle(case_, s, position[k], velocity[k]);
      for (int a = 0; a < dimension(); ++a)
        if (!(r.position[a] >= case_.domain.lo[a] && r.position[a] <= case_.domain.hi[a]))
          throw InputError(case_.path, "domain", "the new particle " + std::to_string(k) + " lies outside the box");
      records.push_back(r);
    }
    try {
      return std::visit([&](auto& e) { return e.add_particles(records); }, run_.engine_variant());
    } catch (const std::invalid_argument& refused) {
      throw InputError(case_.path, "", refused.what());
    }
  }
  void remove_particles(const std::vector<std::uint32_t>& ids) override {
    std::visit([&](auto& e) { e.remove_particles(ids); }, run_.engine_variant());
  }

 private:
  void take_up_writes() override {
    if (std::exchange(written_, false))
      std::visit([](auto& e) { e.restart_from_current_state(); }, run_.engine_variant());
  }
};

}  // namespace

int run_dem(const CaseConfig& c, const RunOptions& options) { return DemRun(c, options).run(); }

std::unique_ptr<RunSession> open_dem_session(const CaseConfig& c, const RunOptions& options) {
  return std::make_unique<DemSession>(c, options);
}

}  // namespace grainflow::run
