// A [[geometry]] wall's own keys (point, normal, radius, ...) as its table gave them, defaults filled
// in by its type, in the order the type reads them: the case types stay free of any one wall type.
// The type's file (walls/) reads and checks these keys and builds its shape from them; the case
// writer writes them back in the same order.
#pragma once

#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow {

class TomlReader;

struct GeometryKey {
  bool operator==(const GeometryKey&) const = default;
  enum class Kind { number, vector, boolean, text };
  std::string key;
  Kind kind = Kind::number;
  Vec3 value;        // a number in x; a boolean as 0 or 1 in x
  std::string text;  // a text's (a file's path)
};

class GeometryKeys {
 public:
  bool operator==(const GeometryKeys&) const = default;  // the case writer's round-trip test

  bool has(std::string_view key) const { return find(key) != nullptr; }
  double number(std::string_view key) const { return at(key).value.x; }
  Vec3 vector(std::string_view key) const { return at(key).value; }
  bool boolean(std::string_view key) const { return at(key).value.x != 0.0; }
  const std::string& text(std::string_view key) const { return at(key).text; }
  void set_number(std::string_view key, double v) { set(key, GeometryKey::Kind::number, {v, 0.0, 0.0}); }
  void set_vector(std::string_view key, const Vec3& v) { set(key, GeometryKey::Kind::vector, v); }
  void set_boolean(std::string_view key, bool v) { set(key, GeometryKey::Kind::boolean, {v ? 1.0 : 0.0, 0.0, 0.0}); }
  void set_text(std::string_view key, std::string v) {
    set(key, GeometryKey::Kind::text, {});
    for (auto& e : entries_)
      if (e.key == key) e.text = std::move(v);
  }
  const std::vector<GeometryKey>& entries() const { return entries_; }

 private:
  const GeometryKey* find(std::string_view key) const {
    for (const auto& e : entries_)
      if (e.key == key) return &e;
    return nullptr;
  }
  // A key the type itself stored; asking for another is a programming error, not an input error.
  const GeometryKey& at(std::string_view key) const {
    if (const GeometryKey* e = find(key)) return *e;
    throw std::logic_error("geometry key '" + std::string(key) + "' was never read");
  }
  void set(std::string_view key, GeometryKey::Kind kind, const Vec3& v) {
    for (auto& e : entries_)
      if (e.key == key) {
        e.kind = kind;
        e.value = v;
        return;
      }
    entries_.push_back({std::string(key), kind, v, {}});
  }
  std::vector<GeometryKey> entries_;
};

// How the case loader reads a wall type it does not know: each registered type (walls/wall_types.hpp)
// hands over one schema.
struct GeometrySchema {
  std::string_view name;     // geometry.type
  std::string_view meaning;  // for messages and docs
  // Reads, checks and defaults the type's own keys of one [[geometry]] table into `out`.
  void (*read)(TomlReader& table, GeometryKeys& out);
};

using GeometrySchemas = std::span<const GeometrySchema>;

}  // namespace grainflow
