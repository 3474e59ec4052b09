#include "grainflow/io/json_writer.hpp"

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

namespace grainflow::io {

std::string json_quote(const std::string& text) {
  std::string out = "\"";
  for (char ch : text) {
    switch (ch) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
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

namespace {

void append_text(const nlohmann::ordered_json& value, std::string& out) {
  using Type = nlohmann::ordered_json::value_t;
  switch (value.type()) {
    case Type::boolean:
      out += value.get<bool>() ? "true" : "false";
      return;
    case Type::number_integer:
      out += std::to_string(value.get<std::int64_t>());
      return;
    case Type::number_unsigned:
      out += std::to_string(value.get<std::uint64_t>());
      return;
    case Type::number_float: {
      const double x = value.get<double>();
      if (!std::isfinite(x)) break;  // null
      char buffer[32];
      std::snprintf(buffer, sizeof buffer, "%.10g", x);
      out += buffer;
      return;
    }
    case Type::string:
      out += json_quote(value.get_ref<const std::string&>());
      return;
    case Type::array: {
      out += '[';
      for (std::size_t i = 0; i < value.size(); ++i) {
        if (i) out += ", ";
        append_text(value[i], out);
      }
      out += ']';
      return;
    }
    case Type::object: {
      out += '{';
      bool first = true;
      for (const auto& [key, item] : value.items()) {
        out += first ? "" : ", ";
        first = false;
        out += json_quote(key) + ": ";
        append_text(item, out);
      }
      out += '}';
      return;
    }
    default:
      break;  // null, and the binary and discarded values JSON text cannot hold
  }
  out += "null";
}

}  // namespace

std::string json_text(const nlohmann::ordered_json& value) {
  std::string out;
  append_text(value, out);
  return out;
}

JsonObject::JsonObject() : fields_(std::make_unique<nlohmann::ordered_json>(nlohmann::ordered_json::object())) {}
JsonObject::~JsonObject() = default;
JsonObject::JsonObject(JsonObject&&) noexcept = default;
JsonObject& JsonObject::operator=(JsonObject&&) noexcept = default;

void JsonObject::number(const std::string& key, double value) {
  if (std::isfinite(value)) {
    (*fields_)[key] = value;
  } else {
    (*fields_)[key] = nullptr;
  }
}
void JsonObject::integer(const std::string& key, long long value) {
  (*fields_)[key] = static_cast<std::int64_t>(value);
}
void JsonObject::string(const std::string& key, const std::string& value) { (*fields_)[key] = value; }
void JsonObject::boolean(const std::string& key, bool value) { (*fields_)[key] = value; }
void JsonObject::strings(const std::string& key, const std::vector<std::string>& values) { (*fields_)[key] = values; }
void JsonObject::value(const std::string& key, const nlohmann::ordered_json& value) { (*fields_)[key] = value; }

void JsonObject::write(std::ostream& out) const {
  out << "{\n";
  std::size_t left = fields_->size();
  for (const auto& [key, value] : fields_->items())
    out << "  " << json_quote(key) << ": " << json_text(value) << (--left > 0 ? ",\n" : "\n");
  out << "}\n";
}

}  // namespace grainflow::io
