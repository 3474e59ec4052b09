// Options of `grainflow run` that are not part of the case: where to write, threads, verbosity.
#pragma once

#include <string>

namespace grainflow::app {

struct RunOptions {
  std::string output_directory;
  int threads = 1;
  bool quiet = false;
};

}  // namespace grainflow::app
