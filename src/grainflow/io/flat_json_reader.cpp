#include "grainflow/io/flat_json_reader.hpp"

#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

namespace grainflow::io {

namespace {

using Json = nlohmann::ordered_json;

// nlohmann's "[json.exception.parse_error.101] parse error at line 1, column 7: syntax error ..."
// as "invalid JSON at line 1, column 7: syntax error ...".
JsonParseError json_parse_error(const std::exception& e) {
  const std::string what = e.what();
  const std::string marker = "parse error at ";
  const auto at = what.find(marker);
  if (at == std::string::npos) return JsonParseError("invalid JSON: " + what);
  return JsonParseError("invalid JSON at " + what.substr(at + marker.size()));
}

// Keeps the scalars of the top-level object as SAX events arrive: the events of numbers carry
// their literal (integers, whose literal is canonical, are spelled again from their value).
class FlatFieldsHandler : public nlohmann::json_sax<Json> {
 public:
  FlatJsonFields fields;

  bool null() override { return scalar({FlatJsonValue::Kind::null, ""}); }
  bool boolean(bool value) override { return scalar({FlatJsonValue::Kind::boolean, value ? "true" : "false"}); }
  bool number_integer(number_integer_t value) override {
    // Only a literal with a minus sign arrives here ("0" comes as unsigned): "-0" keeps its sign.
    return scalar({FlatJsonValue::Kind::number, value == 0 ? "-0" : std::to_string(value)});
  }
  bool number_unsigned(number_unsigned_t value) override {
    return scalar({FlatJsonValue::Kind::number, std::to_string(value)});
  }
  bool number_float(number_float_t, const string_t& literal) override {
    return scalar({FlatJsonValue::Kind::number, literal});
  }
  bool string(string_t& value) override { return scalar({FlatJsonValue::Kind::string, value}); }
  bool binary(binary_t&) override { return true; }  // not produced by a text parser
  bool start_object(std::size_t) override { return open(); }
  bool key(string_t& key) override {
    key_ = key;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override {
    if (depth_ == 0) throw JsonParseError("invalid JSON: the top level is an array, not an object");
    return open();
  }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    throw json_parse_error(e);
  }

 private:
  bool open() {
    ++depth_;
    return true;
  }
  bool close() {
    --depth_;
    return true;
  }
  bool scalar(FlatJsonValue value) {
    if (depth_ == 0) throw JsonParseError("invalid JSON: the top level is a single value, not an object");
    if (depth_ > 1) return true;  // inside a field's array or object: skipped
    for (auto& field : fields)
      if (field.first == key_) {
        field.second = std::move(value);
        return true;
      }
    fields.emplace_back(key_, std::move(value));
    return true;
  }

  int depth_ = 0;
  std::string key_;
};

}  // namespace

FlatJsonFields read_flat_json(std::string_view text) {
  FlatFieldsHandler handler;
  Json::sax_parse(text, &handler);
  return std::move(handler.fields);
}

FlatJsonFields read_flat_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw JsonParseError("cannot read " + path);
  std::ostringstream buffer;
  buffer << in.rdbuf();
  try {
    return read_flat_json(buffer.str());
  } catch (const JsonParseError& e) {
    throw JsonParseError(path + ": " + e.what());
  }
}

Json read_json(std::string_view text) {
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& e) {
    throw json_parse_error(e);
  }
}

}  // namespace grainflow::io
