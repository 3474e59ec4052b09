// The process's first step, before its command line is read: MPI initialised when a launcher
// (mpirun) started it, else nothing. Here so that the program (app/) needs no layer below run/.
#pragma once

#include "grainflow/parallel/communicator.hpp"

namespace grainflow::run {

inline void start_process(int& argc, char**& argv) { parallel::Communicator::start(argc, argv); }

}  // namespace grainflow::run
