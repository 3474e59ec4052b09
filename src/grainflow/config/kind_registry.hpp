// A registry of the named kinds a case key chooses among (rolling models, restitution laws, wall
// conditions): one table per kind with each entry's name, enumerator and meaning, and the lookups
// the parser and the engines share, so that a name the table lacks is an error everywhere instead
// of falling through to some default.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace grainflow {

template <class Kind>
struct KindEntry {
  Kind kind;
  const char* name;
  const char* meaning;  // one line, for messages and documentation
};

// "a, b, c": the registered names in table order.
template <class Kind, std::size_t N>
std::string registered_kind_names(const KindEntry<Kind> (&table)[N]) {
  std::string out;
  for (std::size_t i = 0; i < N; ++i) out += std::string(i == 0 ? "" : ", ") + table[i].name;
  return out;
}

// The kind registered as `name`; `what` names the registry in the message ("rolling model").
// Throws std::invalid_argument listing the registered names for any other name.
template <class Kind, std::size_t N>
Kind registered_kind(const KindEntry<Kind> (&table)[N], std::string_view name, std::string_view what) {
  for (const auto& entry : table)
    if (name == entry.name) return entry.kind;
  throw std::invalid_argument("unknown " + std::string(what) + " '" + std::string(name) +
                              "' (registered: " + registered_kind_names(table) + ")");
}

}  // namespace grainflow
