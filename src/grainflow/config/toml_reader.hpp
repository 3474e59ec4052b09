// Reads one TOML table into typed values, remembering which keys were used so that any key the
// schema does not know is reported (with file, key and reason) instead of silently ignored.
#pragma once

#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "grainflow/core/vec3.hpp"

namespace grainflow {

class TomlReader {
 public:
  // `prefix` is the dotted path of this table ("" for the root); `overridden` the keys set by --set.
  TomlReader(std::string file, const toml::table* table, std::string prefix, const std::set<std::string>* overridden);

  bool has(const std::string& key) const;
  double number(const std::string& key, double fallback);
  double required_number(const std::string& key);
  std::int64_t integer(const std::string& key, std::int64_t fallback);
  bool boolean(const std::string& key, bool fallback);
  std::string string(const std::string& key, const std::string& fallback);
  // A string that must be a registered name: `to_kind` is a registry's lookup (kind_registry.hpp),
  // whose refusal of an unknown name (listing the registered ones) becomes this key's error.
  template <class ToKind>
  std::string registered_name(const std::string& key, ToKind to_kind, const std::string& fallback) {
    std::string name = string(key, fallback);
    try {
      to_kind(name);
    } catch (const std::invalid_argument& e) {
      fail(key, e.what());
    }
    return name;
  }
  Vec3 vec3(const std::string& key, const Vec3& fallback);
  Vec3 required_vec3(const std::string& key);

  TomlReader table(const std::string& key);  // an absent table reads as empty
  std::vector<TomlReader> array_of_tables(const std::string& key);
  const toml::node* raw(const std::string& key);  // marks the key used

  // Throws InputError for the first key of this table that was never read.
  void reject_unknown_keys() const;

  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;
  std::string full_key(const std::string& key) const { return prefix_.empty() ? key : prefix_ + "." + key; }
  const std::string& file() const { return file_; }

 private:
  const toml::node* find(const std::string& key);
  std::string source_of(const std::string& key) const;

  std::string file_;
  const toml::table* table_;
  std::string prefix_;
  const std::set<std::string>* overridden_;
  std::set<std::string> used_;
};

// Applies `--set a.b.c=VALUE` to a parsed document. VALUE is TOML (numbers, strings, booleans,
// arrays); a bare word that is not valid TOML is taken as a string. Numeric path segments index
// arrays (species.0.count). Returns the dotted key that was set.
std::string apply_override(toml::table& root, const std::string& assignment, const std::string& file);

}  // namespace grainflow
