// Checkpoints in a run driver: reading one for --restart (checked against the case before anything
// runs), and writing the driver's whole state (engine and every accumulator) through one function
// that serves both directions, so what is saved and what is restored cannot drift apart.
#pragma once

#include <string>

#include "grainflow/run/run_support.hpp"
#include "grainflow/config/case_config.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/core/version.hpp"
#include "grainflow/io/checkpoint_file.hpp"
#include "grainflow/io/state_archive.hpp"
#include "grainflow/parallel/communicator.hpp"

namespace grainflow::run {

// Reads `path` and checks it belongs to a case of this engine, dimension and particle count. Written
// by as many MPI ranks as this run has, it gives this rank's own state; by another number, the
// portable state (a DEM run's, checkpoint.portable).
io::Checkpoint read_restart(const std::string& path, const CaseConfig& c, long long particles,
                            const parallel::Communicator& comm = parallel::Communicator::world());

// The folder holding `checkpoint` (and the copies of the HDF5 streams written with it).
std::string checkpoint_folder(const std::string& checkpoint);

// summary.json's error for a run stopped by SIGINT / SIGTERM at `time` (its unit: " s" or ""), with
// the command that continues it from the checkpoint written.
std::string interrupted_message(int signal, double time, const std::string& unit, const CaseConfig& c,
                                const std::string& dir);

// Writes dir/checkpoint.h5 from `transfer(archive)`, which must be the same function a restart
// reads with. On several MPI ranks every rank calls it, with its own state; rank 0 gathers the
// states and writes the file with `particles` (all of them, rank 0's gathered view).
// `portable` (rank 0's is written): the run's state for a restart on another rank count, or empty.
template <class Transfer>
void write_run_checkpoint(const std::string& dir, const CaseConfig& c, const ParticleStore& particles, double time,
                          long long step, Transfer&& transfer,
                          const parallel::Communicator& comm = parallel::Communicator::world(),
                          const std::vector<std::uint8_t>& portable = {}) {
  io::StateArchive ar = io::StateArchive::for_writing();
  transfer(ar);
  std::vector<std::vector<std::uint8_t>> states;
  if (comm.size() > 1) states = comm.gather(ar.bytes());
  else states.push_back(ar.bytes());
  if (!comm.root()) return;
  io::CheckpointHeader h;
  h.engine = c.engine.kind;
  h.dimension = c.engine.dimension;
  h.particles = static_cast<long long>(particles.size());
  h.time = time;
  h.step = step;
  h.version = kVersion;
  h.case_path = c.path;
  h.case_overrides = join_overrides(c.overrides);
  h.ranks = comm.size();
  io::write_checkpoint(dir + "/checkpoint.h5", h, particles, states, portable);
}

template <class Transfer>
void restore_run_state(const io::Checkpoint& checkpoint, const std::string& path, Transfer&& transfer) {
  io::StateArchive ar = io::StateArchive::for_reading(checkpoint.state, path);
  transfer(ar);
  ar.expect_end();
}

}  // namespace grainflow::run
