// The readers of the sampling tables the parser still reads itself ([trajectory], [tracers],
// [coarse_grain]), and the key readers those tables share with an observer's
// own schema (config/observer_schema.hpp): the sampling window and a list of particle ids.
#pragma once

#include <cstdint>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/config/toml_reader.hpp"

namespace grainflow {

// The `particles` key's array of particle ids ([trajectory], [tracers]).
std::vector<std::uint32_t> read_particle_ids(TomlReader& r, const toml::array& list);

// The sampling window keys: start (< 0 when absent: the caller's default) and samples, at least `fewest`.
void read_sampling(TomlReader& r, double& start, long long& samples, long long fewest);

// Each reads its table from `top` when the case has it (the engine and protocol it needs checked).
void read_trajectory(TomlReader& top, CaseConfig& c);
void read_tracers(TomlReader& top, CaseConfig& c);
void read_coarse_grain(TomlReader& top, CaseConfig& c);

}  // namespace grainflow
