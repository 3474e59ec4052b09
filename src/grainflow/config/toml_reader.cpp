#include "grainflow/config/toml_reader.hpp"

#include <cmath>
#include <sstream>

#include "grainflow/core/error.hpp"

namespace grainflow {

TomlReader::TomlReader(std::string file, const toml::table* table, std::string prefix,
                       const std::set<std::string>* overridden)
    : file_(std::move(file)), table_(table), prefix_(std::move(prefix)), overridden_(overridden) {}

bool TomlReader::has(const std::string& key) const { return table_ && table_->contains(key); }

const toml::node* TomlReader::find(const std::string& key) {
  used_.insert(key);
  if (!table_) return nullptr;
  return table_->get(key);
}

const toml::node* TomlReader::raw(const std::string& key) { return find(key); }

std::string TomlReader::source_of(const std::string& key) const {
  if (overridden_ && overridden_->count(full_key(key))) return file_ + " (--set)";
  return file_;
}

void TomlReader::fail(const std::string& key, const std::string& reason) const {
  throw InputError(source_of(key), full_key(key), reason);
}

static bool to_double(const toml::node& node, double& out) {
  if (auto v = node.as_floating_point()) {
    out = v->get();
    return true;
  }
  if (auto v = node.as_integer()) {
    out = static_cast<double>(v->get());
    return true;
  }
  return false;
}

double TomlReader::number(const std::string& key, double fallback) {
  const toml::node* node = find(key);
  if (!node) return fallback;
  double value = 0.0;
  if (!to_double(*node, value)) fail(key, "expected a number");
  if (!std::isfinite(value)) fail(key, "must be finite");
  return value;
}

double TomlReader::required_number(const std::string& key) {
  if (!has(key)) fail(key, "is required");
  return number(key, 0.0);
}

std::int64_t TomlReader::integer(const std::string& key, std::int64_t fallback) {
  const toml::node* node = find(key);
  if (!node) return fallback;
  if (auto v = node->as_integer()) return v->get();
  fail(key, "expected an integer");
}

bool TomlReader::boolean(const std::string& key, bool fallback) {
  const toml::node* node = find(key);
  if (!node) return fallback;
  if (auto v = node->as_boolean()) return v->get();
  fail(key, "expected true or false");
}

std::string TomlReader::string(const std::string& key, const std::string& fallback) {
  const toml::node* node = find(key);
  if (!node) return fallback;
  if (auto v = node->as_string()) return v->get();
  fail(key, "expected a string");
}

Vec3 TomlReader::vec3(const std::string& key, const Vec3& fallback) {
  const toml::node* node = find(key);
  if (!node) return fallback;
  const toml::array* array = node->as_array();
  if (!array || array->size() != 3) fail(key, "expected an array of 3 numbers");
  Vec3 out;
  for (int axis = 0; axis < 3; ++axis) {
    double value = 0.0;
    if (!to_double(*array->get(axis), value)) fail(key, "expected an array of 3 numbers");
    if (!std::isfinite(value)) fail(key, "must be finite");
    out[axis] = value;
  }
  return out;
}

Vec3 TomlReader::required_vec3(const std::string& key) {
  if (!has(key)) fail(key, "is required");
  return vec3(key, Vec3{});
}

TomlReader TomlReader::table(const std::string& key) {
  const toml::node* node = find(key);
  if (node && !node->is_table()) fail(key, "expected a table");
  return TomlReader(file_, node ? node->as_table() : nullptr, full_key(key), overridden_);
}

std::vector<TomlReader> TomlReader::array_of_tables(const std::string& key) {
  std::vector<TomlReader> out;
  const toml::node* node = find(key);
  if (!node) return out;
  const toml::array* array = node->as_array();
  if (!array) fail(key, "expected an array of tables ([[" + key + "]])");
  for (std::size_t i = 0; i < array->size(); ++i) {
    const toml::table* entry = array->get(i)->as_table();
    if (!entry) fail(key, "expected an array of tables ([[" + key + "]])");
    out.emplace_back(file_, entry, full_key(key) + "." + std::to_string(i), overridden_);
  }
  return out;
}

void TomlReader::reject_unknown_keys() const {
  if (!table_) return;
  for (const auto& [key, node] : *table_) {
    const std::string name(key.str());
    if (!used_.count(name)) fail(name, "unknown key (see docs/CASE_FILES.md for the valid keys)");
  }
}

static bool is_index(const std::string& segment) {
  return !segment.empty() && segment.find_first_not_of("0123456789") == std::string::npos;
}

std::string apply_override(toml::table& root, const std::string& assignment, const std::string& file) {
  const auto equals = assignment.find('=');
  if (equals == std::string::npos || equals == 0) throw InputError(file + " (--set)", assignment, "expected KEY=VALUE");
  const std::string key = assignment.substr(0, equals);
  const std::string text = assignment.substr(equals + 1);

  std::vector<std::string> path;
  std::stringstream stream(key);
  for (std::string segment; std::getline(stream, segment, '.');) {
    if (segment.empty()) throw InputError(file + " (--set)", key, "empty path segment");
    path.push_back(segment);
  }

  toml::table parsed;
  try {
    parsed = toml::parse("value = " + text);
  } catch (const toml::parse_error&) {
    parsed = toml::table{};
    parsed.insert("value", text);  // a bare word: take it as a string
  }

  toml::node* current = &root;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const std::string& segment = path[i];
    if (auto* table = current->as_table()) {
      if (!table->contains(segment)) table->insert(segment, toml::table{});
      current = table->get(segment);
    } else if (auto* array = current->as_array()) {
      if (!is_index(segment)) throw InputError(file + " (--set)", key, "'" + segment + "' must be an index");
      const std::size_t index = std::stoul(segment);
      if (index >= array->size()) throw InputError(file + " (--set)", key, "index " + segment + " is out of range");
      current = array->get(index);
    } else {
      throw InputError(file + " (--set)", key, "'" + segment + "' is not a table");
    }
  }
  toml::node* value = parsed.get("value");
  if (auto* table = current->as_table()) {
    table->insert_or_assign(path.back(), *value);
  } else if (auto* array = current->as_array()) {
    if (!is_index(path.back()) || std::stoul(path.back()) >= array->size())
      throw InputError(file + " (--set)", key, "index out of range");
    array->replace(array->begin() + static_cast<std::ptrdiff_t>(std::stoul(path.back())), *value);
  } else {
    throw InputError(file + " (--set)", key, "parent is not a table");
  }
  return key;
}

}  // namespace grainflow
