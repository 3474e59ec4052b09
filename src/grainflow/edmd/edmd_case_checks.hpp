// The checks of a case for the edmd engine that need more than one key. Throws InputError.
#pragma once

#include "grainflow/config/case_config.hpp"

namespace grainflow::edmd {

void validate_edmd_case(const CaseConfig& c);

}  // namespace grainflow::edmd
