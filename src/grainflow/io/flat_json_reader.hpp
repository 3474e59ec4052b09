// Reads JSON through nlohmann's parser. read_flat_json: the scalar fields of one object, such as a
// run's summary.json: numbers (kept as written, so nothing is lost in a round trip), strings,
// booleans and nulls, in file order; fields whose values are arrays or objects are parsed and
// skipped. read_json: a whole value, nested ones included. Anything that is not valid JSON (or, for
// the flat reader, not an object at the top) is an error.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace grainflow::io {

struct FlatJsonValue {
  enum class Kind { number, string, boolean, null };
  Kind kind = Kind::null;
  // number: the literal as written ("12", "-1.5e-3"); string: the decoded text (UTF-8);
  // boolean: "true" or "false"; null: "".
  std::string text;
  // A number written without fraction or exponent.
  bool is_integer() const { return kind == Kind::number && text.find_first_of(".eE") == std::string::npos; }
};

using FlatJsonFields = std::vector<std::pair<std::string, FlatJsonValue>>;

class JsonParseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The scalar fields of the object in `text`. A key given twice keeps its first position and its
// last value. Throws JsonParseError (with the line and column) on malformed input.
FlatJsonFields read_flat_json(std::string_view text);

// The same for a file; throws JsonParseError naming the file when it cannot be read or parsed.
FlatJsonFields read_flat_json_file(const std::string& path);

// The value in `text`, objects in file order; throws JsonParseError (with the line and column).
nlohmann::ordered_json read_json(std::string_view text);

}  // namespace grainflow::io
