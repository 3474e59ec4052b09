// Options of `grainflow run` that are not part of the case: where to write, threads, verbosity.
#pragma once

#include <string>

namespace grainflow::run {

struct RunOptions {
  std::string output_directory;
  int threads = 1;
  bool quiet = false;
  std::string restart;      // checkpoint.h5 to continue from ("" = start afresh)
  bool echo_errors = true;  // repeat summary.json's errors on stderr (`calibrate` reports its trials itself)
};

}  // namespace grainflow::run
