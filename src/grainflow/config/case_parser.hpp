// Case text plus --set overrides → CaseConfig, each key checked on its own (type, range, which
// engine takes it), or InputError naming the file, the key and the reason. The contact laws' keys
// are read through the schemas the laws hand over, an observer's own table through the schema its
// observer hands over; the checks that combine keys and models are the run layer's
// (run/case_loader.hpp). Reads the particle file of init = "file".
#pragma once

#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/config/contact_schema.hpp"
#include "grainflow/config/geometry_keys.hpp"
#include "grainflow/config/observer_schema.hpp"

namespace grainflow {

CaseConfig parse_case(const std::string& text, const std::string& label, const std::vector<std::string>& overrides,
                      ContactSchemas schemas, ObserverSchemas observer_schemas, GeometrySchemas geometry_schemas);

// The text of a case file, or InputError.
std::string read_case_file(const std::string& path);

}  // namespace grainflow
