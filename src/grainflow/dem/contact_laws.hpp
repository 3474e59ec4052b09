// The table from case-file contact models to contact laws, and their parameters for particle
// pairs and for each wall. Adding a law: its header, one entry in DemEngineVariant, one make_*.
#pragma once

#include <variant>
#include <vector>

#include "grainflow/core/case_config.hpp"
#include "grainflow/dem/dem_engine.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/dem/linear_dashpot.hpp"
#include "grainflow/dem/walton_braun.hpp"

namespace grainflow::dem {

using DemEngineVariant = std::variant<DemEngine<WaltonBraun>, DemEngine<LinearDashpot>>;

// Builds the engine for the case's contact model from an initial state; with `domain`, as one of
// several MPI ranks (`state` is then the whole initial state, the same on every rank).
DemEngineVariant make_engine(const CaseConfig& c, DemState state, int threads, const EngineDomain* domain = nullptr);

}  // namespace grainflow::dem
