// How the case loader reads the tables of a contact law it does not know: each registered law
// (dem/contact_law_registry.hpp) hands the loader one ContactSchema, so the schema of [contact] and
// of a wall's law keys lives in the law's own file.
#pragma once

#include <span>
#include <string>
#include <string_view>

#include "grainflow/config/contact_parameters.hpp"

namespace grainflow {

class TomlReader;

struct ContactSchema {
  std::string_view name;                        // contact.model
  std::span<const std::string_view> keys;       // its keys in [contact], besides model and friction
  std::span<const std::string_view> wall_keys;  // its keys in [walls.FACE], besides friction
  // Reads, checks and defaults the law's keys of [contact] / of one wall table into `out`.
  void (*read)(TomlReader& table, ContactParameters& out);
  void (*read_wall)(TomlReader& table, ContactParameters& out);
};

using ContactSchemas = std::span<const ContactSchema>;

// The schema called `name`, or null.
inline const ContactSchema* find_schema(ContactSchemas schemas, std::string_view name) {
  for (const auto& s : schemas)
    if (s.name == name) return &s;
  return nullptr;
}

// "a, b, c": the registered names, for error messages.
inline std::string schema_names(ContactSchemas schemas) {
  std::string text;
  for (const auto& s : schemas) text += (text.empty() ? "" : ", ") + std::string(s.name);
  return text;
}

}  // namespace grainflow
