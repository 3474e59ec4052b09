// The registered observers: every output a run can write besides its time series, final state and
// summary, each with the engines it serves, the case tables that ask for it and how it is made.
// A run builds the ones its case asks for, in this order, which is also the order in which they
// sample, go into checkpoints and write.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "grainflow/config/observer_schema.hpp"
#include "grainflow/observe/observer.hpp"
#include "grainflow/observe/run_context.hpp"

namespace grainflow::run {

enum class EngineKind { dem, edmd };

// `start`: the frame the run will offer them (observers may keep a pointer to it), showing the
// initial state with every particle of the run (before any decomposition over MPI ranks).
std::vector<std::unique_ptr<observe::Observer>> make_observers(EngineKind engine, const observe::RunContext& run,
                                                               const observe::Frame& start);

// The schemas of the registered observers that own their case table, in registry order: the case
// loader reads, checks and writes those tables through them.
ObserverSchemas observer_schemas();

// The names of the registered observers of `engine`, in order (docs and tests).
std::vector<std::string> observer_names(EngineKind engine);

}  // namespace grainflow::run
