#include "grainflow/io/json_writer.hpp"

#include <cmath>
#include <cstdio>

namespace grainflow::io {

std::string json_quote(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    switch (ch) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(ch) < 0x20) {
          char buffer[8];
          std::snprintf(buffer, sizeof buffer, "\\u%04x", ch);
          out += buffer;
        } else {
          out += ch;
        }
    }
  }
  return out + "\"";
}

void JsonObject::number(const std::string& key, double value) {
  if (!std::isfinite(value)) {
    entries_.emplace_back(key, "null");  // JSON has no NaN or Inf
    return;
  }
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  entries_.emplace_back(key, buffer);
}
void JsonObject::integer(const std::string& key, long long value) { entries_.emplace_back(key, std::to_string(value)); }
void JsonObject::string(const std::string& key, const std::string& value) { entries_.emplace_back(key, json_quote(value)); }
void JsonObject::boolean(const std::string& key, bool value) { entries_.emplace_back(key, value ? "true" : "false"); }
void JsonObject::strings(const std::string& key, const std::vector<std::string>& values) {
  std::string encoded = "[";
  for (std::size_t i = 0; i < values.size(); ++i) encoded += (i ? ", " : "") + json_quote(values[i]);
  entries_.emplace_back(key, encoded + "]");
}

void JsonObject::write(std::ostream& out) const {
  out << "{\n";
  for (std::size_t i = 0; i < entries_.size(); ++i)
    out << "  " << json_quote(entries_[i].first) << ": " << entries_[i].second << (i + 1 < entries_.size() ? ",\n" : "\n");
  out << "}\n";
}

}  // namespace grainflow::io
