#include "grainflow/run/checkpointing.hpp"

#include <filesystem>

#include "grainflow/run/interrupt.hpp"

namespace grainflow::run {

std::string checkpoint_folder(const std::string& checkpoint) {
  const std::filesystem::path folder = std::filesystem::path(checkpoint).parent_path();
  return folder.empty() ? "." : folder.string();
}

namespace {
// How a run of `ranks` ranks is started again: a checkpoint continues on as many.
std::string launcher(int ranks) { return ranks > 1 ? "mpirun -np " + std::to_string(ranks) + " " : ""; }
}  // namespace

std::string interrupted_message(int signal, double time, const std::string& unit, const CaseConfig& c,
                                const std::string& dir) {
  return std::string("interrupted by ") + signal_name(signal) + " at t = " + std::to_string(time) + unit +
         "; continue with: " + launcher(parallel::Communicator::world().size()) + "grainflow run " + c.path +
         " --restart " + dir + "/checkpoint.h5";
}

io::Checkpoint read_restart(const std::string& path, const CaseConfig& c, long long particles,
                            const parallel::Communicator& comm) {
  const io::CheckpointHeader header = io::read_checkpoint_header(path);
  // The same rank count continues exactly from each rank's own state; another one from the
  // portable state, which DEM checkpoints hold.
  const bool exact = header.ranks == comm.size();
  if (!exact && c.engine.kind == "dem" && !io::has_portable_state(path))
    throw InputError(path, "",
                     "this checkpoint was written by " + std::to_string(header.ranks) +
                         " MPI rank(s) without a portable state (an older version): continue on " +
                         std::to_string(header.ranks));
  io::Checkpoint checkpoint = io::read_checkpoint(path, exact ? comm.rank() : io::kPortable);
  const auto& h = checkpoint.header;
  auto refuse = [&](const std::string& what) {
    throw InputError(path, "", "this checkpoint cannot continue case '" + c.path + "': " + what);
  };
  if (h.engine != c.engine.kind) refuse("it is from a '" + h.engine + "' run, the case is '" + c.engine.kind + "'");
  if (h.dimension != c.engine.dimension)
    refuse("it is " + std::to_string(h.dimension) + "D, the case " + std::to_string(c.engine.dimension) + "D");
  if (h.particles != particles)
    refuse("it holds " + std::to_string(h.particles) + " particles, the case makes " + std::to_string(particles));
  if (h.ranks != comm.size() && c.engine.kind != "dem")
    refuse("it was written by " + std::to_string(h.ranks) + " MPI rank(s), this run has " +
           std::to_string(comm.size()));
  if (h.time > c.run.duration)
    refuse("it is at t = " + std::to_string(h.time) + ", past the case's run.duration = " +
           std::to_string(c.run.duration) + " (raise it with --set run.duration=...)");
  return checkpoint;
}

}  // namespace grainflow::run
