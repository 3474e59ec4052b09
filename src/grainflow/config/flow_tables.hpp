// [[insertion]] and [[outlet]]: where particles enter a run and where they leave it (silos,
// hoppers, chutes fed from above). Read after [[species]] and [[geometry]], whose names they use.
#pragma once

#include "grainflow/config/case_config.hpp"
#include "grainflow/config/toml_reader.hpp"

namespace grainflow {

void read_insertions(TomlReader& top, CaseConfig& c);
void read_outlets(TomlReader& top, CaseConfig& c);

}  // namespace grainflow
