// What an observer is built from besides its own case table: the case, the run's folder, and the
// quantities the engine derived from the case (the time step, the reference diameter, the gravity
// axis), so that observers need no engine to be made.
#pragma once

#include <string>

#include "grainflow/config/case_config.hpp"
#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/parallel/communicator.hpp"

namespace grainflow::observe {

struct RunContext {
  const CaseConfig* c = nullptr;
  int dimension = 3;
  int gravity_axis = 1;
  double reference_diameter = 0.0;  // m
  double time_step = 0.0;           // s, soft spheres; 0 in an event-driven run
  double restitution = 0.0;         // the binary contact's (soft spheres)
  std::string directory;            // the run's output folder
  bool writes = true;               // rank 0 holds the files
  RankReduce ranks;                 // sums over MPI ranks (the identity on one)
  const parallel::Communicator* comm = nullptr;
};

}  // namespace grainflow::observe
