// The case parser's wall tables: [walls.FACE] and [[geometry]], and the check every law-keyed table
// shares. Internal to config/ (case_parser.cpp calls them).
#pragma once

#include <span>
#include <string_view>

#include "grainflow/config/case_config.hpp"
#include "grainflow/config/contact_schema.hpp"
#include "grainflow/config/geometry_keys.hpp"
#include "grainflow/config/toml_reader.hpp"

namespace grainflow {

// A key of another registered contact law is named as such rather than as unknown.
void reject_other_laws_keys(TomlReader& r, ContactSchemas schemas, const ContactSchema& law,
                            std::span<const std::string_view> ContactSchema::*keys);

// [walls]
void read_walls(TomlReader& top, CaseConfig& c, ContactSchemas schemas);

// [[geometry]]: walls of any registered type, each reading its own keys.
void read_geometry(TomlReader& top, CaseConfig& c, ContactSchemas schemas, GeometrySchemas types);

}  // namespace grainflow
