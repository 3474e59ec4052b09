#include "grainflow/run/edmd_run.hpp"
#include "grainflow/run/run_session_over.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <unistd.h>
#include <variant>

#include "grainflow/analysis/steady_state.hpp"
#include "grainflow/run/observer_registry.hpp"
#include "grainflow/run/run_support.hpp"
#include "grainflow/run/steady_state_report.hpp"
#include "grainflow/run/checkpointing.hpp"
#include "grainflow/run/interrupt.hpp"
#include "grainflow/parallel/communicator.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/core/version.hpp"
#include "grainflow/edmd/edmd_engine.hpp"
#include "grainflow/edmd/fault_checks.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/io/vtu_writer.hpp"
#include "grainflow/observe/global_sample.hpp"

namespace grainflow::run {
namespace {

struct Row {
  double time;
  observe::GlobalSample global;
  long long collisions, wall_collisions, events;
  double pressure;    // over the interval ending at `time`: kinetic (instantaneous) + collisional
  double dissipated;  // J since the start
  engine_api::EnergyBudget budget;
  double budget_residual;
  edmd::ServoState servo;
};

using EdmdVariant = std::variant<edmd::EdmdEngine<2>, edmd::EdmdEngine<3>>;
constexpr double kNeverTime = std::numeric_limits<double>::infinity();

// One event-driven run: built from the case, advanced from sample time to sample time, written.
// Each member function is one stage; the state they share is the members below.
class EdmdRun {
 public:
  EdmdRun(const CaseConfig& c, const RunOptions& options);
  int run();  // `grainflow run`: start, advance to the case's end, write every output

  // The same in pieces (a RunSession): start, advance to `until` (at most the case's end; stops
  // early at an interrupt, a collision budget, or a failure, which advance reports (true) and
  // finish() writes into summary.json), then the outputs.
  void begin();
  bool advance(double until);
  int finish();
  int take_interrupt() { return std::exchange(interrupted, 0); }
  bool finished() const { return done; }
  EdmdVariant& engine_variant() { return *engine; }
  const std::string& output_directory() const { return dir; }
  const std::string& first_error() const { return errors.front(); }

 private:
  template <class E>
  double current_measure(const E& e) const;
  template <class E>
  void record(E& e);
  template <class E>
  void transfer(io::StateArchive& ar, E& e);
  template <class E>
  void checkpoint(E& e);
  template <class E>
  void start(E& e);
  template <class E>
  void event_loop(E& e, double until);
  template <class E>
  void bind_frame(E& e);
  template <class E>
  const observe::Frame& frame_now(E& e);
  template <class E>
  void listen_to_collisions(E& e);
  long long collision_budget() const;
  template <class E>
  bool end_segment(E& e);
  double next_sample_time() const;
  double first_profile_sample() const;
  void write_timeseries() const;
  template <class E>
  void write_outputs(E& e);

  const CaseConfig& c;
  const RunOptions& options;
  const int dim;
  std::optional<io::Checkpoint> restart;
  std::unique_ptr<EdmdVariant> engine;  // built in place: an engine is not moved once built
  std::string dir;
  std::optional<io::PvdSeries> snapshots;
  // The case's observers (run/observer_registry.cpp): strip profiles, collision stresses, the
  // trajectory, each sampled at the times it asks for, and the frame they see.
  std::vector<std::unique_ptr<observe::Observer>> observers;
  observe::Frame frame;
  io::JsonObject summary;
  observe::OutputSink sink;
  double measure = 1.0;  // box area in 2D, volume in 3D (a Couette cell's follows its walls and width)
  int gravity_axis = 1;
  std::vector<Row> rows;
  std::vector<std::string> errors, warnings;
  std::optional<Progress> progress;
  std::chrono::steady_clock::time_point wall_start;
  double wall_seconds = 0.0;  // to the end of the loop, before the outputs are written
  int exit_status = 0;
  double last_time = 0.0, last_virial = 0.0;
  // Long-term sums from average_start: time-integrated kinetic "m v^2" sum and the virial.
  double average_kinetic = 0.0, average_temperature = 0.0, average_virial = 0.0, average_span = 0.0;
  long average_rows = 0;
  double end_time = 0.0;
  // Rows, snapshots, samples and checkpoints each on their own exact grid k * interval.
  long row = 1, shot = 1, checkpoints = 1;
  int interrupted = 0;
  long long first_events = 0, first_collisions = 0;  // before this process (a restart's checkpoint)
  observe::RunContext context;
  // Campbell's protocol (run.protocol = "campbell"): the segment under way, where it began (its
  // first row of `rows`) and whether the last one judged passed the section 2.5 check.
  int segment = 1;
  long long segment_start_collisions = 0;
  std::size_t segment_first_row = 0;
  bool segment_converged = false;
  bool begun = false, done = false, stopped = false;  // stopped: the collision budget or Campbell's check ended it
};

EdmdRun::EdmdRun(const CaseConfig& case_config, const RunOptions& run_options)
    : c(case_config), options(run_options), dim(case_config.engine.dimension) {
  namespace fs = std::filesystem;
  if (parallel::Communicator::world().size() > 1)
    throw InputError(c.path, "engine.kind",
                     "the event-driven engine runs on one rank; start it without mpirun (docs/SCALING.md says how it "
                     "would be parallelised)");
  edmd::EdmdState initial = edmd::build_edmd_state(c);
  if (!options.restart.empty())
    restart = read_restart(options.restart, c, static_cast<long long>(initial.particles.size()));
  engine.reset(dim == 2 ? new EdmdVariant(std::in_place_index<0>, std::move(initial))
                        : new EdmdVariant(std::in_place_index<1>, std::move(initial)));
  fs::create_directories(options.output_directory);
  dir = options.output_directory;
  if (c.output.snapshot_interval > 0.0) snapshots.emplace(dir + "/snapshots");
  std::visit([&](auto& e) { bind_frame(e); }, *engine);
  const int along_gravity = std::fabs(c.gravity.x) > std::fabs(c.gravity.y) ? 0 : 1;
  context = observe::RunContext{&c, dim, along_gravity, c.species.front().diameter, 0.0, 0.0, dir, true, {}, nullptr};
  observers = make_observers(EngineKind::edmd, context, frame);
  sink = observe::OutputSink{dir, true, &summary, &warnings};
  for (int a = 0; a < dim; ++a) measure *= c.domain.length(a);
  gravity_axis = std::fabs(c.gravity.x) > std::fabs(c.gravity.y) ? 0 : 1;
  progress.emplace(!options.quiet && ::isatty(2), c.run.duration);
  wall_start = std::chrono::steady_clock::now();
  end_time = c.run.duration;
}

template <class E>
double EdmdRun::current_measure(const E& e) const {
  if (!c.servo.enabled) return measure;
  return e.servo().gap * e.servo().width * (dim == 3 ? c.domain.length(2) : 1.0);
}

// The frame observers see: pointers into the engine's state (built in place, so they stay valid).
template <class E>
void EdmdRun::bind_frame(E& e) {
  const auto& st = e.state();
  frame.dimension = dim;
  frame.particles = &st.particles;
  frame.box = &st.box;
  frame.walls = FaceWalls(st.walls);
  frame.wall_contacts = [&e](const observe::Frame::WallContactVisit& visit) { e.for_each_rolling(visit); };
  frame_now(e);
}

template <class E>
const observe::Frame& EdmdRun::frame_now(E& e) {
  frame.time = e.state().time;
  frame.collisions = e.counters().collisions;
  return frame;
}

// The engine reports every collision to the observer that asks for them now (at most one does).
template <class E>
void EdmdRun::listen_to_collisions(E& e) {
  engine_api::CollisionObserver* listener = nullptr;
  for (auto& o : observers)
    if (auto* l = o->collision_observer()) listener = l;
  e.set_observer(listener);
}

double EdmdRun::next_sample_time() const {
  double t = kNeverTime;
  for (const auto& o : observers) t = std::min(t, o->next_time());
  return t;
}

// When the long-term averages began (NaN before), for the convergence check: the first observer
// that keeps averages (the strip profiles) says.
double EdmdRun::first_profile_sample() const {
  for (const auto& o : observers)
    if (const double t = o->first_sample_time(); !std::isnan(t)) return t;
  return std::numeric_limits<double>::quiet_NaN();
}

template <class E>
void EdmdRun::record(E& e) {
  const auto& st = e.state();
  edmd::check_faults(st);  // NaN or a particle through a wall: stop here
  auto& k = e.counters();
  Row r{};
  r.time = st.time;
  r.global = observe::sample_global(st.particles, gravity_axis, dim);
  r.collisions = k.collisions;
  r.wall_collisions = k.wall_collisions;
  r.events = k.events;
  r.dissipated = k.dissipated;
  r.budget = e.energy_budget();
  r.budget_residual = r.budget.residual(k.start_energy);
  r.servo = e.servo();
  const double span = st.time - last_time;
  // Kinetic part from velocities about the mass-mean one (as the temperature), so a mean flow is
  // not counted as pressure: sum m v'^2 = d M T.
  const double kinetic = dim * r.global.mass * r.global.granular_temperature;
  r.pressure = (kinetic + (span > 0.0 ? (k.virial - last_virial) / span : 0.0)) / (dim * current_measure(e));
  const bool averaging = st.time > c.output.average_start && k.collisions >= c.output.average_start_collisions;
  if (averaging && span > 0.0) {
    average_kinetic += kinetic;
    average_temperature += r.global.granular_temperature;
    ++average_rows;
    average_virial += k.virial - last_virial;
    average_span += span;
  }
  last_time = st.time;
  last_virial = k.virial;
  rows.push_back(r);
}

// The run's whole state, one function for both directions (checkpoint and restart).
template <class E>
void EdmdRun::transfer(io::StateArchive& ar, E& e) {
  ar.tag("edmd run with observers");
  ar(e, rows, last_time, last_virial, average_kinetic, average_temperature, average_virial, average_span, average_rows);
  ar(row, shot, checkpoints);
  ar(segment, segment_start_collisions, segment_first_row, segment_converged);
  if (snapshots) ar(*snapshots);
  for (auto& o : observers) {
    ar.tag(o->name());
    o->serialize(ar);
  }
  ar.tag("end of edmd run");
}

// Streamed files are copied beside the checkpoint first: a checkpoint never counts more samples
// than its copies hold.
template <class E>
void EdmdRun::checkpoint(E& e) {
  for (auto& o : observers) o->save_streams(dir);
  write_run_checkpoint(dir, c, e.state().particles, e.state().time, e.counters().events,
                       [&](io::StateArchive& ar) { transfer(ar, e); });
}

template <class E>
void EdmdRun::start(E& e) {
  if (restart) {
    restore_run_state(*restart, options.restart, [&](io::StateArchive& ar) { transfer(ar, e); });
    listen_to_collisions(e);
    for (auto& o : observers) o->resume_streams(checkpoint_folder(options.restart));
    first_events = e.counters().events;
    first_collisions = e.counters().collisions;
  } else {
    record(e);
    if (snapshots) snapshots->add(e.state().particles, e.state().time);
  }
}

template <class E>
void EdmdRun::event_loop(E& e, double until) {
  const double checkpoint_interval = c.output.checkpoint_interval;
  try {
    while (e.state().time < until && !stopped) {
      // Between advances every particle is current: a checkpoint here continues exactly.
      if ((interrupted = pending_interrupt()) != 0) break;
      const double next_row = std::min(end_time, row * c.output.interval);
      const double next_shot = snapshots ? grid_time(shot, c.output.snapshot_interval, end_time) : kNeverTime;
      double t = std::min({next_row, next_shot, next_sample_time(), until});
      // A collision budget (the run's, or a Campbell segment's) ends at its last collision exactly,
      // with a row there.
      const bool budget_spent = e.advance_to(t, collision_budget());
      t = e.state().time;
      if (next_sample_time() <= t) {
        const observe::Frame& now = frame_now(e);
        for (auto& o : observers)
          if (o->next_time() <= t) o->sample(now);
        listen_to_collisions(e);
      }
      if (snapshots && next_shot <= t) {
        snapshots->add(e.state().particles, e.state().time);
        ++shot;
      }
      if (next_row > t && !budget_spent) continue;
      if (next_row <= t) ++row;
      record(e);
      progress->update(t);
      if (t >= end_time) break;
      if ((stopped = c.run.collisions > 0 && e.counters().collisions >= c.run.collisions)) break;
      if ((stopped = c.run.protocol == "campbell" &&
                     e.counters().collisions - segment_start_collisions >= c.run.segment_collisions &&
                     end_segment(e)))
        break;
      if (checkpoint_interval > 0.0 && t >= checkpoints * checkpoint_interval * (1.0 - 1e-12)) {
        while (t >= checkpoints * checkpoint_interval * (1.0 - 1e-12)) ++checkpoints;
        checkpoint(e);
      }
    }
  } catch (const RunError&) {
    e.synchronize(e.state().time);  // the outputs show every particle at one instant
    throw;
  }
}

// The particle-collision count at which the run or the current Campbell segment ends.
long long EdmdRun::collision_budget() const {
  long long budget = edmd::EdmdEngine<3>::kNoCollisionLimit;
  if (c.run.collisions > 0) budget = c.run.collisions;
  if (c.run.protocol == "campbell") budget = std::min(budget, segment_start_collisions + c.run.segment_collisions);
  return budget;
}

// The end of one of Campbell's segments: the section 2.5 check on its kinetic-energy rows. It has
// converged when the whole segment is steady (no transient to leave out); then, or after the last
// segment allowed, the run stops (true). Otherwise the next segment starts here with fresh averages,
// as Campbell's next run started from the last one's final state.
template <class E>
bool EdmdRun::end_segment(E& e) {
  std::vector<double> time, energy;
  for (std::size_t r = segment_first_row; r < rows.size(); ++r) {
    time.push_back(rows[r].time);
    energy.push_back(rows[r].global.kinetic_energy);
  }
  const analysis::SteadyState steady = analysis::detect_steady_state(time, energy);
  segment_converged = steady.steady_from && *steady.steady_from <= time.front();
  if (segment_converged || segment >= c.run.max_segments) return true;
  ++segment;
  segment_start_collisions = e.counters().collisions;
  segment_first_row = rows.size() - 1;
  observers = make_observers(EngineKind::edmd, context, frame_now(e));
  listen_to_collisions(e);
  average_kinetic = average_temperature = average_virial = average_span = 0.0;
  average_rows = 0;
  return false;
}

void EdmdRun::begin() {
  if (begun) return;
  begun = true;
  try {
    std::visit([&](auto& e) { start(e); }, *engine);
  } catch (const RunError& error) {
    errors.push_back(error.what());
    exit_status = 1;
  }
}

bool EdmdRun::advance(double until) {
  begin();
  if (exit_status != 0) return true;
  try {
    std::visit([&](auto& e) { event_loop(e, std::min(until, end_time)); }, *engine);
  } catch (const RunError& error) {
    errors.push_back(error.what());
    exit_status = 1;
  }
  return exit_status != 0;
}

int EdmdRun::finish() {
  if (done) return exit_status;
  done = true;
  begin();
  if (interrupted != 0) {
    const double t = std::visit([](auto& e) { return e.state().time; }, *engine);
    errors.push_back(interrupted_message(interrupted, t, "", c, dir));
    exit_status = 128 + interrupted;
  }
  progress->finish();
  wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  std::visit([&](auto& e) { write_outputs(e); }, *engine);
  return exit_status;
}

int EdmdRun::run() {
  advance(end_time);
  // The end, or an interruption: a checkpoint to continue from (the end's, to run longer).
  if (exit_status == 0 && (interrupted != 0 || c.output.checkpoint_interval > 0.0)) {
    try {
      std::visit([&](auto& e) { checkpoint(e); }, *engine);
    } catch (const RunError& error) {
      errors.push_back(error.what());
      exit_status = 1;
    }
  }
  return finish();
}

void EdmdRun::write_timeseries() const {
  io::write_atomically(dir + "/timeseries.csv", [&](std::ostream& out) {
    out << "# units: time s, energies J, granular_temperature m^2/s^2 (per degree of freedom), pressure "
        << (dim == 2 ? "N/m" : "Pa")
        << " (kinetic + collisional virial over the interval), dissipated J; energy budget since the start:"
           " energy_input (gravity along periodic axes, walls, boundaries: sliding images, re-separation shifts), "
           "energy_change (kinetic + rotational +"
           " potential), energy_dissipated J, energy_budget_residual (input - change - dissipated) / max(|input|,"
           " |dissipated|)\n";
    const bool servo = c.servo.enabled;
    if (servo)
      out << "# servo: gap and width m, wall_speed m/s (> 0 opening), wall_stress as pressure, top_speed m/s\n";
    out << "time,kinetic_energy,rotational_energy,granular_temperature,collisions,wall_collisions,events,pressure,"
           "dissipated,energy_input,energy_change,energy_dissipated,energy_budget_residual"
        << (servo ? ",gap,width,wall_speed,wall_stress,top_speed" : "") << "\n";
    for (const auto& r : rows) {
      out << r.time << ',' << r.global.kinetic_energy << ',' << r.global.rotational_energy << ','
          << r.global.granular_temperature << ',' << r.collisions << ',' << r.wall_collisions << ',' << r.events << ','
          << r.pressure << ',' << r.dissipated << ',' << r.budget.input() << ',' << r.budget.change << ','
          << r.budget.dissipated << ',' << r.budget_residual;
      if (servo)
        out << ',' << r.servo.gap << ',' << r.servo.width << ',' << r.servo.wall_speed << ',' << r.servo.measured_stress
            << ',' << r.servo.top_speed;
      out << '\n';
    }
  });
}

template <class E>
void EdmdRun::write_outputs(E& e) {
  const auto& st = e.state();
  const auto& k = e.counters();
  const std::size_t n = st.particles.size();
  double solids = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double r = st.particles.radius[i];
    solids += dim == 2 ? M_PI * r * r : 4.0 / 3.0 * M_PI * r * r * r;
  }
  write_timeseries();
  write_final_state(dir + "/final_state.csv", st.particles, st.species);

  const double volume = current_measure(e);
  const double number_density = n / volume;
  const double mean_mass = rows.empty() || rows.back().global.mass == 0.0 ? 0.0 : rows.back().global.mass / n;
  double pressure = 0.0, temperature = 0.0;
  if (average_rows > 0 && average_span > 0.0) {
    temperature = average_temperature / average_rows;
    pressure = (average_kinetic / average_rows + average_virial / average_span) / (dim * volume);
  }
  const auto global = observe::sample_global(st.particles, gravity_axis, dim);
  summary.string("engine", "edmd");
  summary.integer("dimension", dim);
  summary.integer("particles", static_cast<long long>(n));
  summary.string("case", c.path);
  summary.string("case_overrides", join_overrides(c.overrides));
  summary.string("version", kVersion);
  summary.number("simulated_time", st.time);
  summary.number("wall_seconds", wall_seconds);
  summary.integer("events", k.events);
  summary.integer("collisions", k.collisions);
  summary.integer("wall_collisions", k.wall_collisions);
  summary.integer("cell_crossings", k.cell_crossings);
  summary.integer("stale_events", k.stale);
  summary.integer("neighbor_list_rebuilds", k.list_rebuilds);
  summary.integer("rolling_starts", k.rolling_starts);
  // The TC model's share: collisions it made elastic and smooth (Campbell's rules have no such model).
  summary.number("tc_collision_fraction", k.collisions > 0 ? double(k.tc_collisions) / double(k.collisions) : 0.0);
  summary.number("tc_wall_collision_fraction",
                 k.wall_collisions > 0 ? double(k.tc_wall_collisions) / double(k.wall_collisions) : 0.0);
  summary.number("events_per_second", wall_seconds > 0.0 ? (k.events - first_events) / wall_seconds : 0.0);
  summary.number("collisions_per_second", wall_seconds > 0.0 ? (k.collisions - first_collisions) / wall_seconds : 0.0);
  if (restart) summary.string("restarted_from", options.restart);
  summary.number("pressure", pressure);
  summary.number("packing_fraction", solids / volume);
  summary.number("compressibility_factor",
                 temperature > 0.0 && mean_mass > 0.0 ? pressure / (number_density * mean_mass * temperature) : 0.0);
  summary.number("kinetic_energy", global.kinetic_energy);
  summary.number("rotational_energy", global.rotational_energy);
  summary.number("granular_temperature", temperature > 0.0 ? temperature : global.granular_temperature);
  summary.number("dissipated_energy", k.dissipated);
  write_energy_budget(e.energy_budget(), k.start_energy, summary);
  if (c.servo.enabled) {
    summary.integer("servo_updates", k.servo_updates);
    summary.number("wall_gap", e.servo().gap);
    summary.number("cell_width", e.servo().width);
  }
  e.set_observer(nullptr);
  const observe::Frame& last = frame_now(e);
  for (auto& o : observers) o->write(last, sink);
  std::vector<double> row_time, row_energy;
  const bool segmented = c.run.protocol == "campbell";
  for (std::size_t r = segmented ? segment_first_row : 0; r < rows.size(); ++r)
    row_time.push_back(rows[r].time), row_energy.push_back(rows[r].global.kinetic_energy);
  summary.string("protocol", c.run.protocol);
  if (segmented) {
    summary.integer("segments", segment);
    summary.boolean("segment_converged", segment_converged);
    summary.number("segment_start_time", rows[segment_first_row].time);
    summary.integer("segment_collisions", k.collisions - segment_start_collisions);
    if (!segment_converged && exit_status == 0 && interrupted == 0)
      warnings.push_back(
          "Campbell's protocol: none of the " + std::to_string(segment) + " segments of " +
          std::to_string(c.run.segment_collisions) +
          " collisions passed the section 2.5 check (the averages are the last segment's; raise run.max_segments)");
  }
  const double first = first_profile_sample();
  report_steady_state(row_time, row_energy, std::isfinite(first) ? first : c.output.average_start, summary, warnings);
  for (auto& o : observers) o->finish(sink);
  exit_status = finish_summary(summary, dir, errors, warnings, exit_status);
}

// A RunSession over an EdmdRun: advanced by simulated time.
class EdmdSession final : public RunSessionOver<EdmdRun> {
 public:
  using RunSessionOver::RunSessionOver;
  bool event_driven() const override { return true; }
  long long steps() override {
    return std::visit([](auto& e) { return e.counters().events; }, run_.engine_variant());
  }
  double time_step() const override { return 0.0; }
  long long last_step() const override { return 0; }
  void advance_steps(long long) override {
    throw InputError(case_.path, "engine.kind", "the event-driven engine has no time step: advance it by a time");
  }
  void advance_time(double dt) override {
    refuse_when_finished();
    refuse_negative(dt, "a time");
    const double target = time() + dt;
    refuse_beyond(target > end_time() * (1.0 + 1e-12), "time " + std::to_string(end_time()),
                  "time " + std::to_string(target));
    advance_driver(std::min(target, end_time()));
  }
  void particles_written(bool positions) override {
    if (positions) throw InputError(case_.path, "", "the event-driven engine's positions are read-only");
    written_ = true;
  }
  std::vector<std::uint32_t> add_particles(const std::vector<int>&, const std::vector<Vec3>&,
                                           const std::vector<Vec3>&) override {
    throw InputError(case_.path, "engine.kind", "the event-driven engine's particles are the case's: none are added");
  }
  void remove_particles(const std::vector<std::uint32_t>&) override {
    throw InputError(case_.path, "engine.kind", "the event-driven engine's particles are the case's: none are removed");
  }

 private:
  void take_up_writes() override {
    if (std::exchange(written_, false)) std::visit([](auto& e) { e.take_velocities(); }, run_.engine_variant());
  }
};

}  // namespace

int run_edmd(const CaseConfig& c, const RunOptions& options) { return EdmdRun(c, options).run(); }

std::unique_ptr<RunSession> open_edmd_session(const CaseConfig& c, const RunOptions& options) {
  return std::make_unique<EdmdSession>(c, options);
}

}  // namespace grainflow::run
