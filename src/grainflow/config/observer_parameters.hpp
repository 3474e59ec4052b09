// An observer's case table as its schema read it (config/observer_schema.hpp): each key's value, a
// flag, an integer, a number or a text, with the defaults the observer fills in, in the order it
// reads them. The case types stay free of any one observer: the observer's file reads these keys
// and reads them back when it is built, and the case writer writes them in the same order.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace grainflow {

class ObserverParameters {
 public:
  using Value = std::variant<bool, long long, double, std::string>;

  bool operator==(const ObserverParameters&) const = default;  // the case writer's round-trip test

  bool has(std::string_view key) const { return find(key) != nullptr; }
  // A key the observer itself stored, of the type it stored; asking for another is a programming
  // error, not an input error.
  bool flag(std::string_view key) const { return get<bool>(key); }
  long long integer(std::string_view key) const { return get<long long>(key); }
  double number(std::string_view key) const { return get<double>(key); }
  const std::string& text(std::string_view key) const { return get<std::string>(key); }

  void set_flag(std::string_view key, bool value) { set(key, value); }
  void set_integer(std::string_view key, long long value) { set(key, value); }
  void set_number(std::string_view key, double value) { set(key, value); }
  void set_text(std::string_view key, std::string value) { set(key, std::move(value)); }

  const std::vector<std::pair<std::string, Value>>& entries() const { return entries_; }

 private:
  const Value* find(std::string_view key) const {
    for (const auto& [name, value] : entries_)
      if (name == key) return &value;
    return nullptr;
  }
  template <class T>
  const T& get(std::string_view key) const {
    const Value* value = find(key);
    if (!value || !std::holds_alternative<T>(*value))
      throw std::logic_error("observer parameter '" + std::string(key) + "' was never read as this type");
    return std::get<T>(*value);
  }
  void set(std::string_view key, Value value) {
    for (auto& [name, stored] : entries_)
      if (name == key) {
        stored = std::move(value);
        return;
      }
    entries_.emplace_back(std::string(key), std::move(value));
  }
  std::vector<std::pair<std::string, Value>> entries_;
};

}  // namespace grainflow
