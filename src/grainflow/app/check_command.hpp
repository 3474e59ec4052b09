// `grainflow check`: prints the derived quantities of a validated case (section 2.5, 4.1).
#pragma once

#include <ostream>

#include "grainflow/config/case_config.hpp"

namespace grainflow::app {

void print_check(const CaseConfig& c, std::ostream& out);

}  // namespace grainflow::app
