// The tables of the case that belong to observers with a schema of their own
// (config/observer_schema.hpp), by table name, in the order the schemas were read: a table present
// is its observer asked for.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "grainflow/config/observer_parameters.hpp"

namespace grainflow {

class ObserverTables {
 public:
  bool operator==(const ObserverTables&) const = default;  // the case writer's round-trip test

  bool has(std::string_view table) const { return find(table) != nullptr; }
  const ObserverParameters& at(std::string_view table) const {
    if (const ObserverParameters* found = find(table)) return *found;
    throw std::logic_error("observer table [" + std::string(table) + "] is not in the case");
  }
  // The table called `table`, added empty at the end if absent.
  ObserverParameters& add(std::string_view table) {
    for (auto& [name, parameters] : tables_)
      if (name == table) return parameters;
    return tables_.emplace_back(std::string(table), ObserverParameters{}).second;
  }
  // Drops the table: its observer is no longer asked for.
  void erase(std::string_view table) {
    std::erase_if(tables_, [&](const auto& entry) { return entry.first == table; });
  }
  const std::vector<std::pair<std::string, ObserverParameters>>& entries() const { return tables_; }

 private:
  const ObserverParameters* find(std::string_view table) const {
    for (const auto& [name, parameters] : tables_)
      if (name == table) return &parameters;
    return nullptr;
  }
  std::vector<std::pair<std::string, ObserverParameters>> tables_;
};

}  // namespace grainflow
