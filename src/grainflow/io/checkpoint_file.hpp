// checkpoint.h5: a run's exact state, to continue it with `grainflow run CASE --restart FILE`.
// The file holds what a person wants to look at (attributes naming the run, the particles as
// datasets for h5py or h5dump) and, in /state, the bytes every component wrote through its
// serialize() (io/state_archive.hpp), which the restart reads back; a run of several MPI ranks
// leaves one such state per rank, gathered into the one file by rank 0. Written under a temporary
// name and renamed, so a run killed while writing leaves the previous checkpoint intact.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "grainflow/particles/particle_store.hpp"

namespace grainflow::io {

struct CheckpointHeader {
  std::string engine;  // "dem" | "edmd"
  long long dimension = 3;
  long long particles = 0;
  double time = 0.0;   // s (or the case's time unit)
  long long step = 0;  // dem: steps; edmd: events
  std::string version, case_path, case_overrides;
  long long ranks = 1;  // MPI ranks that wrote it: each rank's state is its own (same count to restart)
};

// `states`: one per rank (header.ranks of them), in /state and /state_rank_1, /state_rank_2, ...;
// `portable` (if not empty): the run's state in a form a restart on another rank count reads, in
// /portable.
void write_checkpoint(const std::string& path, const CheckpointHeader& header, const ParticleStore& particles,
                      const std::vector<std::vector<std::uint8_t>>& states,
                      const std::vector<std::uint8_t>& portable = {});

struct Checkpoint {
  CheckpointHeader header;
  std::vector<std::uint8_t> state;  // the reading rank's, or the portable state
  bool portable = false;
};

// `rank`'s state, or with rank = kPortable the portable one. Throw InputError naming the file
// (missing, not a checkpoint, damaged, no portable state).
inline constexpr int kPortable = -1;
Checkpoint read_checkpoint(const std::string& path, int rank = 0);
bool has_portable_state(const std::string& path);
CheckpointHeader read_checkpoint_header(const std::string& path);

}  // namespace grainflow::io
