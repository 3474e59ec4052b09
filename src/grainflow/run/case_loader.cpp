#include "grainflow/run/case_loader.hpp"

#include "grainflow/config/case_parser.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/run/case_validation.hpp"
#include "grainflow/run/observer_registry.hpp"
#include "grainflow/walls/wall_types.hpp"

namespace grainflow {

CaseConfig load_case_from_string(const std::string& text, const std::string& label,
                                 const std::vector<std::string>& overrides) {
  CaseConfig c = parse_case(text, label, overrides, dem::contact_schemas(), run::observer_schemas(), walls::geometry_schemas());
  validate_case(c);
  return c;
}

CaseConfig load_case(const std::string& path, const std::vector<std::string>& overrides) {
  return load_case_from_string(read_case_file(path), path, overrides);
}

CaseConfig load_case_unvalidated(const std::string& path, const std::vector<std::string>& overrides) {
  return parse_case(read_case_file(path), path, overrides, dem::contact_schemas(), run::observer_schemas(), walls::geometry_schemas());
}

}  // namespace grainflow
