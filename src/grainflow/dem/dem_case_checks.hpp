// The checks of a case for the dem engine that need more than one key. Throws InputError.
#pragma once

#include "grainflow/config/case_config.hpp"

namespace grainflow::dem {

void validate_dem_case(const CaseConfig& c);

}  // namespace grainflow::dem
