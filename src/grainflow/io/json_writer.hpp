// The JSON records of a run (summary.json, run_log.json, ...): one object whose fields keep the
// order they were added in, held as nlohmann's ordered_json, so a field may also be an array or an
// object. Written in the layout the records have always had, which nlohmann's dump does not give:
// one field a line, a nested value on its field's line, numbers in %.10g (dump prints the shortest
// exact form, "3.0" for 3, and exponents only from 1e15), strings' bytes as they are.
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace grainflow::io {

class JsonObject {
 public:
  JsonObject();
  ~JsonObject();
  JsonObject(JsonObject&&) noexcept;
  JsonObject& operator=(JsonObject&&) noexcept;

  // A key added again keeps its first place and takes the new value.
  void number(const std::string& key, double value);  // NaN and infinities as null: JSON has neither
  void integer(const std::string& key, long long value);
  void string(const std::string& key, const std::string& value);
  void boolean(const std::string& key, bool value);
  void strings(const std::string& key, const std::vector<std::string>& values);
  void value(const std::string& key, const nlohmann::ordered_json& value);  // any value, nested ones too

  const nlohmann::ordered_json& fields() const { return *fields_; }
  void write(std::ostream& out) const;

 private:
  std::unique_ptr<nlohmann::ordered_json> fields_;  // behind a pointer: few includers need the library
};

// A JSON string literal of `text`: quotes, backslashes and control characters escaped, other bytes kept.
std::string json_quote(const std::string& text);

// `value` in the records' layout on one line: "[1, 2]", {"a": 0.5}, numbers in %.10g.
std::string json_text(const nlohmann::ordered_json& value);

}  // namespace grainflow::io
