// The stages of one DEM run (run/dem_run.cpp): `grainflow run` goes through them in one call, a
// RunSession (run/run_session.hpp, the Python module) one piece at a time.
#pragma once

#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/dem/engine_factory.hpp"
#include "grainflow/io/checkpoint_file.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/io/state_archive.hpp"
#include "grainflow/io/vtu_writer.hpp"
#include "grainflow/observe/bed_surface.hpp"
#include "grainflow/observe/global_sample.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/observe/run_context.hpp"
#include "grainflow/observe/zone_profile.hpp"
#include "grainflow/parallel/communicator.hpp"
#include "grainflow/run/clog_watch.hpp"
#include "grainflow/run/dem_parallel_view.hpp"
#include "grainflow/run/dem_portable_state.hpp"
#include "grainflow/run/dem_timeseries.hpp"
#include "grainflow/run/dem_wall_outputs.hpp"
#include "grainflow/run/run_options.hpp"
#include "grainflow/run/run_support.hpp"

namespace grainflow::run {

// One DEM run: built from the case (observers, schedules, engine), then stepped, then written.
// Each member function is one stage; the state they share is the members below.
class DemRun {
 public:
  DemRun(const CaseConfig& c, const RunOptions& options);
  int run();  // `grainflow run`: start, step to the case's end, write every output

  // The same in pieces (a RunSession): start, steps up to `last` (at most the case's last step;
  // stops early at an interrupt, interrupted() says which), then the outputs. A failure inside
  // advance is kept for finish(), which writes it into summary.json; advance reports it (true).
  void begin();
  bool advance(long last);
  int finish();
  int take_interrupt() { return std::exchange(interrupted, 0); }
  bool finished() const { return done; }
  long last_step() const { return total_steps; }
  double time_step() const { return dt; }
  dem::DemEngineVariant& engine_variant() { return *engine; }
  const std::string& output_directory() const { return dir; }
  const std::string& first_error() const { return errors.front(); }

 private:
  template <class E>
  void transfer(io::StateArchive& ar, E& e);
  template <class E>
  void portable_run(io::StateArchive& ar, E& e);
  template <class E>
  void restore_portable_run(io::StateArchive& ar, E& e);
  template <class E>
  void checkpoint(E& e);
  template <class E>
  const ParticleStore& all_particles(E& e);
  template <class E>
  void record(E& e);
  template <class E>
  void start(E& e);
  template <class E>
  void step_loop(E& e, long last);
  void catch_failures(const std::function<void()>& stage);
  void handle_failure_outside_loop();
  template <class E>
  void bind_frame(E& e);
  template <class E>
  const observe::Frame& frame_now(E& e);
  template <class E>
  void write_outputs(E& e);
  template <class E>
  std::pair<engine_api::EnergyBudget, double> global_energy_budget(const E& e) const;
  void write_summary(long long moving, const observe::GlobalSample& global, long long migrations, long long ghosts);
  template <class E>
  void write_summary_of(E& e, long long moving, const observe::GlobalSample& global, long long migrations,
                        long long ghosts);
  void snapshot(const dem::DemState& st);

  const CaseConfig& c;
  const RunOptions& options;
  const dem::DerivedQuantities derived;
  // Under mpirun with several ranks each rank integrates one box of a grid (dem/domain_exchange.hpp);
  // rank 0 writes every file.
  const parallel::Communicator& comm = parallel::Communicator::world();
  const bool ranks = comm.size() > 1;
  const bool writes = comm.root();
  // Every observer runs on each rank over the rank's own particles and sums over the ranks through
  // this (the identity on one rank); particles are gathered on rank 0 only for final_state.csv.
  const observe::RankReduce rank_reduce = over_ranks(comm);
  long long particle_count = 0;
  std::optional<io::Checkpoint> restart;
  // A checkpoint of another rank count: its particles and clock go into the initial state (the
  // sub-domains are placed on them), its contact memory into the engine once built.
  std::optional<io::StateArchive> portable_restart;
  dem::PortableParticles portable_particles;
  std::string dir;
  std::optional<io::PvdSeries> snapshots;
  std::optional<WallSnapshots> wall_snapshots;  // [[geometry]] walls beside the particles
  int axis = 1;
  double area = 1.0;
  observe::RunContext context;
  // The case's observers (run/observer_registry.cpp), each offered every step, and the frame they
  // see: pointers into the engine's state, the clock refreshed each step.
  std::vector<std::unique_ptr<observe::Observer>> observers;
  observe::Frame frame;
  observe::OutputSink sink;
  io::JsonObject summary;
  std::optional<observe::ZoneProfile> zones_now;  // Lan's cell temperature of each time-series row
  double dt = 0.0;
  long total_steps = 0;
  Schedule output_schedule, snapshot_schedule, checkpoint_schedule;
  std::optional<dem::EngineDomain> domain;
  std::unique_ptr<dem::DemEngineVariant> engine;  // built in place: an engine is not moved once built
  observe::BedSurfaceThresholds bed_thresholds;
  bool floor_below = false;  // bed height needs gravity toward the low face
  std::vector<TimeseriesRow> rows;
  std::vector<std::string> errors, warnings;
  std::optional<Progress> progress;
  std::chrono::steady_clock::time_point wall_start, last_flush;
  double wall_seconds = 0.0;  // to the end of the loop, before the outputs are written
  double max_overlap_seen = 0.0;
  engine_api::EnergyBudget final_budget;  // at the end, over all ranks
  double final_budget_scale = 0.0;        // J, the starting energy (the residual's fallback scale)
  int exit_status = 0;
  long first_step = 0;     // steps before this process's (a restart's checkpoint)
  ParticleStore gathered;  // rank 0: all particles (final_state.csv, a checkpoint's datasets)
  int interrupted = 0;
  bool stopped_together = false;  // MPI: a failure every rank saw at the same output time
  ClogWatch clog;  // [[outlet]]s: whether the orifice clogged
  bool begun = false, done = false;
};


}  // namespace grainflow::run
