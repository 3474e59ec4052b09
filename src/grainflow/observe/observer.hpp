// The one interface through which a run measures and writes, whichever engine runs it. A run
// driver builds the case's observers (run/observer_registry.cpp), hands each a Frame, the engine's
// state seen without its engine, and at the end an OutputSink to write through. An observer keeps
// its own schedule: a soft-sphere run offers it every step, an event-driven run stops at every
// next_time() it asks for. It sums over MPI ranks itself (RankReduce) where each rank holds a share,
// and carries its state through checkpoints. Adding an output is one observer file, its registry
// line and its test.
#pragma once

#include <cstdint>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "grainflow/core/face_wall.hpp"
#include "grainflow/core/periodic_box.hpp"
#include "grainflow/core/vec3.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/io/state_archive.hpp"
#include "grainflow/engine_api/collision_observer.hpp"
#include "grainflow/engine_api/coordination.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

inline constexpr double kNoSampleTime = std::numeric_limits<double>::infinity();

// What an observer sees: the run's state at one time. The driver keeps one Frame for the whole
// run, its pointers into the engine's state (which never moves), and refreshes the clock before
// each call, so an observer may keep a pointer to it (a collision observer reads the walls between
// samples).
// The first index k of a sampling grid k * interval at or after `time` (an observer built mid-run,
// as at the start of one of Campbell's segments, samples from there on).
inline long first_grid_index(double time, double interval) {
  return std::max(1L, static_cast<long>(std::floor(time / interval)) + 1);
}

// What the particles exert on one [[geometry]] wall at the last force evaluation: the force and the
// torque about the wall's motion origin where it is now (this MPI rank's share).
struct GeometryLoad {
  std::string name;
  Vec3 force;   // N
  Vec3 torque;  // N m
};

// What has left through one [[outlet]] so far (cumulative; this rank's particles).
struct OutletTally {
  long removed = 0;
  double mass = 0.0;  // kg (kg/m for discs)
};

struct Frame {
  int dimension = 3;
  double time = 0.0;                         // s
  double time_step = 0.0;                    // s, the soft-sphere step that ended at `time`; 0 in an event-driven run
  long step = 0;                             // soft-sphere steps taken
  long long collisions = 0;                  // collisions so far (event-driven: binary particle collisions)
  const ParticleStore* particles = nullptr;  // this rank's, current at `time`
  const PeriodicBox* box = nullptr;
  FaceWalls walls;
  // Per particle of `particles`, what it touches now (soft spheres; a pass over the contacts).
  std::function<std::vector<engine_api::Coordination>()> coordination;
  // Calls visit(i, wall, force) for each particle pressing on a wall between collisions (an
  // event-driven particle rolling on it), with the force the wall exerts.
  using WallContactVisit = std::function<void(std::uint32_t, int, const Vec3&)>;
  std::function<void(const WallContactVisit&)> wall_contacts;
  // Soft spheres: calls visit(i, wall, from, force) for each touching contact once, with the force
  // on particle i and `from` the partner's centre (its image nearest i) or, for a wall (wall >= 0),
  // the contact point on it; a bumpy wall's bump reports as that wall (i the free particle, `from`
  // the bump's centre), so that its load is the wall's.
  using ContactForceVisit = std::function<void(std::uint32_t, int, const Vec3&, const Vec3&)>;
  std::function<void(const ContactForceVisit&)> contact_forces;
  // Soft spheres: each [[geometry]] wall's load, in the case's order; unset without an engine.
  std::function<std::vector<GeometryLoad>()> geometry_loads;
  // Soft spheres: each [[outlet]]'s tally, in the case's order; unset without an engine.
  std::function<std::vector<OutletTally>()> outlet_counts;
};

// Where an observer writes at the end: files in `directory` (on rank 0 only: `writes`), keys of
// summary.json and the warnings the user should read.
struct OutputSink {
  std::string directory;
  bool writes = true;
  io::JsonObject* summary = nullptr;
  std::vector<std::string>* warnings = nullptr;
};

class Observer {
 public:
  virtual ~Observer() = default;
  // Its case table or output file, for checkpoint tags and messages.
  virtual std::string name() const = 0;
  // The next time it wants a frame (an event-driven run advances there); kNoSampleTime: none.
  virtual double next_time() const { return kNoSampleTime; }
  virtual void sample(const Frame& now) = 0;
  // A fresh run's initial state, where the time series takes its t = 0 row (soft spheres).
  virtual void sample_start(const Frame& now) { (void)now; }
  // Soft spheres on several MPI ranks: true when the sample at `step` reads contact forces, whose
  // damping needs the ghosts' velocities at the step's end (the run refreshes them first; they
  // are half a step old otherwise).
  virtual bool reads_contact_forces_at(long step) const {
    (void)step;
    return false;
  }
  // Non-null while it wants every collision reported (the event-driven engine calls it).
  virtual engine_api::CollisionObserver* collision_observer() { return nullptr; }
  // When its long-term averages took their first sample: NaN before that, and for an observer that
  // keeps none. A run judges its steady state from when the averages began.
  virtual double first_sample_time() const { return std::numeric_limits<double>::quiet_NaN(); }

  // Checkpoints: the state it accumulated; the case rebuilds the rest.
  virtual void serialize(io::StateArchive& ar) = 0;
  // The same for a restart on another MPI rank count: the shares each rank holds summed (collective);
  // on reading, `keeper` (one rank) keeps the sums and the others start their shares from zero.
  virtual void save_portable(io::StateArchive& ar) { serialize(ar); }
  virtual void load_portable(io::StateArchive& ar, bool keeper) {
    (void)keeper;
    serialize(ar);
  }
  // Files streamed while running (HDF5) are copied into, and resumed from, a checkpoint's folder.
  virtual void save_streams(const std::string& folder) { (void)folder; }
  virtual void resume_streams(const std::string& folder) { (void)folder; }

  // Mid-run, every so often: what it has written so far, brought up to date (collective).
  virtual void flush(OutputSink& out) { (void)out; }
  // Sampling is over (the end, an interruption or a failure): streams committed, short ones warned of.
  virtual void finish(OutputSink& out) { (void)out; }
  // The files and summary keys, from `last`, the final state. Collective on several ranks.
  virtual void write(const Frame& last, OutputSink& out) {
    (void)last;
    (void)out;
  }
};

}  // namespace grainflow::observe
