// A minimal JSON object writer for summary.json: flat keys with numbers, strings, booleans and
// string lists, written in insertion order.
#pragma once

#include <ostream>
#include <string>
#include <utility>
#include <vector>

namespace grainflow::io {

class JsonObject {
 public:
  void number(const std::string& key, double value);
  void integer(const std::string& key, long long value);
  void string(const std::string& key, const std::string& value);
  void boolean(const std::string& key, bool value);
  void strings(const std::string& key, const std::vector<std::string>& values);
  void write(std::ostream& out) const;

 private:
  std::vector<std::pair<std::string, std::string>> entries_;  // key, encoded value
};

std::string json_quote(const std::string& text);

}  // namespace grainflow::io
