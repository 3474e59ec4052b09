// A case file plus --set overrides → a validated CaseConfig: its keys read with the registered
// contact laws' schemas (config/case_parser.hpp), then the checks that combine keys with the models
// (case_validation.hpp); or InputError
// naming the file, the key and the reason. Nothing is written anywhere.
#pragma once

#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"

namespace grainflow {

CaseConfig load_case(const std::string& path, const std::vector<std::string>& overrides = {});
CaseConfig load_case_from_string(const std::string& text, const std::string& label,
                                 const std::vector<std::string>& overrides = {});

// The case read and each key checked, but without the checks of validate_case that combine keys
// (time step against contact duration, what fits where, ...): for a tool that reads a case before
// it sets the keys those checks depend on (`grainflow calibrate` chooses contact.k1).
CaseConfig load_case_unvalidated(const std::string& path, const std::vector<std::string>& overrides = {});

}  // namespace grainflow
