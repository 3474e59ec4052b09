// `grainflow run`: a case run into its output folder, or continued from a checkpoint (--restart).
#pragma once

#include <string>
#include <vector>

namespace grainflow::run {

// What `grainflow run` was given on its command line.
struct RunCommand {
  std::string case_path;
  std::vector<std::string> overrides;  // --set, in order
  std::string output_directory;        // -o; "" = runs/<case name>, or the checkpoint's folder on a restart
  std::string restart;                 // --restart: checkpoint.h5 to continue from; "" = start afresh
  int threads = 1;
  bool quiet = false;
};

// Loads the case (on a restart with the checkpoint's own --set assignments first), catches
// interrupts and runs the case's engine with its records; returns the exit status. Input errors
// throw InputError before anything is written.
int run_case(const RunCommand& command, const std::vector<std::string>& command_line);

// The overrides a restart loads its case with: the checkpoint's own --set assignments, so that a
// restart needs only the case and the file, then `overrides` (given now: a longer run.duration, say),
// which come after and win. InputError when the checkpoint is of another engine or dimension.
std::vector<std::string> restart_overrides(const std::string& checkpoint, const std::string& case_path,
                                           const std::vector<std::string>& overrides);

}  // namespace grainflow::run
