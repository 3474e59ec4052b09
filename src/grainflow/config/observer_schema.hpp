// How the case loader reads, checks and writes back the table of an observer it does not know:
// each observer with a table of its own hands one ObserverSchema to the observer registry
// (run/observer_registry.cpp), which hands them to the parser and the case's checks, so an
// observer's keys, defaults and checks live in the observer's own file.
#pragma once

#include <span>
#include <string_view>

#include "grainflow/config/observer_parameters.hpp"

namespace grainflow {

class TomlReader;
struct CaseConfig;

// What an observer's checks may hold its keys against besides the case: the run's time step (0
// for the event-driven engine), reference diameter, gravity axis and particle count.
struct ObserverCheckInputs {
  const CaseConfig& c;
  double time_step = 0.0;
  double reference_diameter = 0.0;
  int gravity_axis = 1;
  long particles = 0;
};

struct ObserverSchema {
  std::string_view table;           // [table]; its presence asks for the observer
  std::string_view engine;          // the engine.kind that takes it
  std::string_view engine_refusal;  // why a case of the other engine may not have it
  // Reads, checks and defaults the table's keys into `out` (the parser then refuses any key left unread).
  void (*read)(TomlReader& table, const CaseConfig& c, ObserverParameters& out);
  // The checks that combine its keys with the run (InputError naming the file and key), or null.
  void (*check)(const ObserverParameters& table, const ObserverCheckInputs& run);
};

using ObserverSchemas = std::span<const ObserverSchema>;

}  // namespace grainflow
