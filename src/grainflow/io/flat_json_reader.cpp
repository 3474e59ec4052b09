#include "grainflow/io/flat_json_reader.hpp"

#include <cstdint>
#include <fstream>
#include <sstream>

namespace grainflow::io {

namespace {

class Parser {
 public:
  explicit Parser(std::string_view text) : s_(text) {}

  FlatJsonFields object() {
    FlatJsonFields fields;
    skip_space();
    expect('{');
    skip_space();
    if (peek() == '}') {
      ++i_;
    } else {
      for (;;) {
        skip_space();
        if (peek() != '"') fail("expected a key in double quotes");
        std::string key = string();
        skip_space();
        expect(':');
        skip_space();
        FlatJsonValue value;
        if (scalar(value)) {
          bool replaced = false;
          for (auto& field : fields)
            if (field.first == key) {
              field.second = value;
              replaced = true;
            }
          if (!replaced) fields.emplace_back(std::move(key), std::move(value));
        }
        skip_space();
        if (peek() == ',') {
          ++i_;
          continue;
        }
        expect('}');
        break;
      }
    }
    skip_space();
    if (i_ != s_.size()) fail("unexpected text after the object");
    return fields;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw JsonParseError("invalid JSON at byte " + std::to_string(i_) + ": " + what);
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  void expect(char ch) {
    if (peek() != ch || i_ >= s_.size()) fail(std::string("expected '") + ch + "'");
    ++i_;
  }
  void skip_space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) ++i_;
  }
  bool literal(std::string_view word) {
    if (s_.substr(i_, word.size()) != word) return false;
    i_ += word.size();
    return true;
  }

  // Reads one value; returns true (filling `out`) for a scalar, false after skipping an array or object.
  bool scalar(FlatJsonValue& out) {
    const char ch = peek();
    if (ch == '"') {
      out = {FlatJsonValue::Kind::string, string()};
      return true;
    }
    if (ch == '[' || ch == '{') {
      skip_container();
      return false;
    }
    if (literal("true")) {
      out = {FlatJsonValue::Kind::boolean, "true"};
      return true;
    }
    if (literal("false")) {
      out = {FlatJsonValue::Kind::boolean, "false"};
      return true;
    }
    if (literal("null")) {
      out = {FlatJsonValue::Kind::null, ""};
      return true;
    }
    out = {FlatJsonValue::Kind::number, number()};
    return true;
  }

  void skip_container() {
    if (++depth_ > 512) fail("nested too deeply");
    const char close = peek() == '[' ? ']' : '}';
    ++i_;
    skip_space();
    if (peek() == close) {
      ++i_;
      --depth_;
      return;
    }
    for (;;) {
      skip_space();
      if (close == '}') {
        if (peek() != '"') fail("expected a key in double quotes");
        string();
        skip_space();
        expect(':');
        skip_space();
      }
      FlatJsonValue ignored;
      scalar(ignored);
      skip_space();
      if (peek() == ',') {
        ++i_;
        continue;
      }
      expect(close);
      --depth_;
      return;
    }
  }

  std::string number() {
    const std::size_t start = i_;
    if (peek() == '-') ++i_;
    auto digits = [&] {
      const std::size_t from = i_;
      while (peek() >= '0' && peek() <= '9') ++i_;
      if (i_ == from) fail("expected a value");
    };
    if (peek() == '0') {
      ++i_;
    } else {
      digits();
    }
    if (peek() == '.') {
      ++i_;
      digits();
    }
    if (peek() == 'e' || peek() == 'E') {
      ++i_;
      if (peek() == '+' || peek() == '-') ++i_;
      digits();
    }
    return std::string(s_.substr(start, i_ - start));
  }

  unsigned hex4() {
    unsigned code = 0;
    for (int k = 0; k < 4; ++k) {
      const char ch = peek();
      unsigned digit;
      if (ch >= '0' && ch <= '9') digit = static_cast<unsigned>(ch - '0');
      else if (ch >= 'a' && ch <= 'f') digit = static_cast<unsigned>(ch - 'a' + 10);
      else if (ch >= 'A' && ch <= 'F') digit = static_cast<unsigned>(ch - 'A' + 10);
      else fail("bad \\u escape");
      code = code * 16 + digit;
      ++i_;
    }
    return code;
  }

  static void append_utf8(std::string& out, std::uint32_t code) {
    if (code < 0x80) {
      out += static_cast<char>(code);
    } else if (code < 0x800) {
      out += static_cast<char>(0xC0 | (code >> 6));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else if (code < 0x10000) {
      out += static_cast<char>(0xE0 | (code >> 12));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (code >> 18));
      out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (code & 0x3F));
    }
  }

  std::string string() {
    expect('"');
    std::string out;
    for (;;) {
      if (i_ >= s_.size()) fail("unterminated string");
      const char ch = s_[i_++];
      if (ch == '"') return out;
      if (static_cast<unsigned char>(ch) < 0x20) fail("control character in a string");
      if (ch != '\\') {
        out += ch;
        continue;
      }
      const char escape = peek();
      ++i_;
      switch (escape) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t code = hex4();
          if (code >= 0xD800 && code < 0xDC00 && literal("\\u")) {  // a surrogate pair
            const std::uint32_t low = hex4();
            if (low < 0xDC00 || low >= 0xE000) fail("bad surrogate pair");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          append_utf8(out, code);
          break;
        }
        default: --i_; fail("bad escape in a string");
      }
    }
  }

  std::string_view s_;
  std::size_t i_ = 0;
  int depth_ = 0;
};

}  // namespace

FlatJsonFields read_flat_json(std::string_view text) { return Parser(text).object(); }

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

}  // namespace grainflow::io
