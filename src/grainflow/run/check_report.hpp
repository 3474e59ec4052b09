// `grainflow check`: prints the derived quantities of a validated case (section 2.5, 4.1).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"

namespace grainflow::run {

void print_check(const CaseConfig& c, std::ostream& out);

// Loads the case with its --set overrides (InputError as load_case) and prints its check; returns
// the exit status, 0.
int check_case(const std::string& case_path, const std::vector<std::string>& overrides, std::ostream& out);

}  // namespace grainflow::run
