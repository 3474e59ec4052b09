// The checks of a case for the dem engine that need more than one key. Throws InputError.
#pragma once

#include "grainflow/config/case_config.hpp"
#include "grainflow/dem/derived_quantities.hpp"

namespace grainflow::dem {

// Returns what it derived from the case, for the checks that follow (the observers' tables).
DerivedQuantities validate_dem_case(const CaseConfig& c);

struct DemState;
// [[insertion]] and [[outlet]] against the built state (its walls and insertion regions): an
// outlet a particle can reach, an insertion region in the box, with room, able to hold its rate.
void validate_flows(const CaseConfig& c, const DemState& s);

}  // namespace grainflow::dem
