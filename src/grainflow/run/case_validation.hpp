// Physical and geometric checks on a parsed case that need more than one key: things that fit,
// time steps that resolve contacts, bumpy walls that hold particles. Throws InputError.
#pragma once

#include "grainflow/config/case_config.hpp"

namespace grainflow {

void validate_case(const CaseConfig& c);

}  // namespace grainflow
