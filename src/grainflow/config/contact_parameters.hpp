// A contact law's own keys as its case table gave them, defaults filled in by the law, in the order
// the law reads them. The case types stay free of any one law: a law's file reads these keys, turns
// them into its parameters, and the case writer writes them back in the same order.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace grainflow {

class ContactParameters {
 public:
  bool operator==(const ContactParameters&) const = default;  // the case writer's round-trip test

  bool has(std::string_view key) const { return find(key) != nullptr; }
  // A key the law itself stored; asking for another is a programming error, not an input error.
  double at(std::string_view key) const {
    if (const double* value = find(key)) return *value;
    throw std::logic_error("contact parameter '" + std::string(key) + "' was never read");
  }
  double get(std::string_view key, double fallback) const {
    const double* value = find(key);
    return value ? *value : fallback;
  }
  void set(std::string_view key, double value) {
    for (auto& [name, stored] : entries_)
      if (name == key) {
        stored = value;
        return;
      }
    entries_.emplace_back(std::string(key), value);
  }
  const std::vector<std::pair<std::string, double>>& entries() const { return entries_; }

 private:
  const double* find(std::string_view key) const {
    for (const auto& [name, value] : entries_)
      if (name == key) return &value;
    return nullptr;
  }
  std::vector<std::pair<std::string, double>> entries_;
};

}  // namespace grainflow
