#include "grainflow/run/sweep_plan.hpp"

#include <map>
#include <set>
#include <stdexcept>

#include <toml++/toml.h>

#include "grainflow/core/error.hpp"

namespace grainflow::run {

namespace {

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

// Folder names stay well below the 255 bytes most file systems allow.
constexpr std::size_t kMaxNameLength = 200;

}  // namespace

std::vector<std::string> split_values(const std::string& list) {
  std::vector<std::string> values;
  std::string brackets;  // the open brackets and braces, innermost last
  char quote = 0;        // the quote character of the string we are in, or 0
  std::size_t start = 0;
  auto push = [&](std::size_t end) {
    std::string value = trim(list.substr(start, end - start));
    if (value.empty()) throw std::invalid_argument("empty value in '" + list + "'");
    values.push_back(std::move(value));
    start = end + 1;
  };
  for (std::size_t i = 0; i < list.size(); ++i) {
    const char ch = list[i];
    if (quote) {
      if (ch == '\\' && quote == '"') ++i;  // basic strings have escapes; literal ('...') ones do not
      else if (ch == quote) quote = 0;
    } else if (ch == '"' || ch == '\'') {
      quote = ch;
    } else if (ch == '[' || ch == '{') {
      brackets += ch;
    } else if (ch == ']' || ch == '}') {
      if (brackets.empty() || brackets.back() != (ch == ']' ? '[' : '{'))
        throw std::invalid_argument(std::string("unbalanced '") + ch + "' in '" + list + "'");
      brackets.pop_back();
    } else if (ch == ',' && brackets.empty()) {
      push(i);
    }
  }
  if (quote) throw std::invalid_argument("unterminated string in '" + list + "'");
  if (!brackets.empty())
    throw std::invalid_argument(std::string("unclosed '") + brackets.back() + "' in '" + list + "'");
  push(list.size());
  return values;
}

SweepVariable parse_vary(const std::string& spec, const std::string& label) {
  const std::string source = label + " (--vary)";
  const auto equals = spec.find('=');
  if (equals == std::string::npos) throw InputError(source, spec, "expected KEY=VALUE1,VALUE2,...");
  SweepVariable variable;
  variable.key = trim(spec.substr(0, equals));
  if (variable.key.empty()) throw InputError(source, spec, "expected KEY=VALUE1,VALUE2,... (the key is empty)");
  if (variable.key.find_first_of(" \t") != std::string::npos)
    throw InputError(source, variable.key, "a key has no spaces");
  try {
    variable.values = split_values(spec.substr(equals + 1));
  } catch (const std::invalid_argument& e) {
    throw InputError(source, variable.key, e.what());
  }
  return variable;
}

std::vector<SweepPoint> plan_sweep(const std::vector<SweepVariable>& variables, bool zip, const std::string& label) {
  const std::string source = label + " (--vary)";
  if (variables.empty())
    throw InputError(source, "", "nothing to vary: give at least one --vary KEY=VALUE1,VALUE2,...");
  std::set<std::string> keys;
  for (const auto& variable : variables) {
    if (variable.values.empty()) throw InputError(source, variable.key, "no values");
    if (!keys.insert(variable.key).second) throw InputError(source, variable.key, "is varied twice");
  }

  std::vector<SweepPoint> points;
  if (zip) {
    const std::size_t n = variables.front().values.size();
    for (const auto& variable : variables)
      if (variable.values.size() != n)
        throw InputError(source, variable.key,
                         "--zip needs lists of equal length: '" + variables.front().key + "' has " + std::to_string(n) +
                             " values, '" + variable.key + "' has " + std::to_string(variable.values.size()));
    if (n > kMaxSweepRuns) throw InputError(source, "", "more than " + std::to_string(kMaxSweepRuns) + " runs");
    for (std::size_t i = 0; i < n; ++i) {
      SweepPoint point;
      for (const auto& variable : variables) point.values.push_back(variable.values[i]);
      points.push_back(std::move(point));
    }
  } else {
    std::size_t n = 1;
    for (const auto& variable : variables) {
      n *= variable.values.size();
      if (n > kMaxSweepRuns) throw InputError(source, "", "more than " + std::to_string(kMaxSweepRuns) + " runs");
    }
    std::vector<std::size_t> index(variables.size(), 0);  // an odometer, the last variable fastest
    for (std::size_t r = 0; r < n; ++r) {
      SweepPoint point;
      for (std::size_t v = 0; v < variables.size(); ++v) point.values.push_back(variables[v].values[index[v]]);
      points.push_back(std::move(point));
      for (std::size_t v = variables.size(); v-- > 0;) {
        if (++index[v] < variables[v].values.size()) break;
        index[v] = 0;
      }
    }
  }

  std::set<std::vector<std::string>> seen;
  for (const auto& point : points)
    if (!seen.insert(point.values).second)
      throw InputError(source, "", "the combination " + describe_point(variables, point) + " is listed twice");

  // Names: key=value per variable, joined by '_'. Rare clashes (values that differ only in characters
  // a folder name cannot hold, or names cut for length) get the run's number appended.
  std::vector<std::string> bases;
  std::map<std::string, int> count;
  for (std::size_t r = 0; r < points.size(); ++r) {
    std::string name;
    for (std::size_t v = 0; v < variables.size(); ++v) {
      std::string value = safe_name(display_value(points[r].values[v]));
      if (value.empty()) value = "empty";
      if (v) name += '_';
      name += safe_name(variables[v].key);
      name += '=';
      name += value;
    }
    if (name.size() > kMaxNameLength) name = name.substr(0, kMaxNameLength - 10) + "~" + std::to_string(r + 1);
    ++count[name];
    bases.push_back(std::move(name));
  }
  std::set<std::string> used;
  for (std::size_t r = 0; r < points.size(); ++r) {
    std::string name = count[bases[r]] == 1 ? bases[r] : bases[r] + "~" + std::to_string(r + 1);
    while (used.count(name)) name += "~";
    used.insert(name);
    points[r].name = std::move(name);
  }
  return points;
}

std::vector<std::string> point_overrides(const std::vector<SweepVariable>& variables, const SweepPoint& point) {
  std::vector<std::string> out;
  for (std::size_t v = 0; v < variables.size(); ++v) out.push_back(variables[v].key + "=" + point.values[v]);
  return out;
}

std::string describe_point(const std::vector<SweepVariable>& variables, const SweepPoint& point) {
  std::string out;
  for (std::size_t v = 0; v < variables.size(); ++v) {
    if (v) out += ' ';
    out += variables[v].key;
    out += '=';
    out += point.values[v];
  }
  return out;
}

std::string display_value(const std::string& toml_text) {
  try {
    const toml::table parsed = toml::parse("value = " + toml_text);
    if (const auto* text = parsed.get_as<std::string>("value")) return text->get();
  } catch (const toml::parse_error&) {
    // a bare word: --set takes it as the string itself
  }
  return toml_text;
}

std::string safe_name(const std::string& text) {
  std::string out;
  bool pending = false;  // a run of other characters waits to become one '_'
  for (const char ch : text) {
    const bool keep = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '.' ||
                      ch == '_' || ch == '+' || ch == '-';
    if (!keep) {
      pending = true;
      continue;
    }
    if (pending && !out.empty()) out += '_';
    pending = false;
    out += ch;
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  while (!out.empty() && out.front() == '_') out.erase(out.begin());
  return out;
}

}  // namespace grainflow::run
