// The plan of `grainflow sweep`: the --vary specs (KEY=v1,v2,...) parsed into keys and TOML value
// texts, the combinations (Cartesian product, or element by element with --zip), and a folder name
// per combination that is safe on any file system and unique within the sweep. No I/O here.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace grainflow::run {

// One --vary option: a case key (as --set takes it) and the values it takes, each the TOML text of
// one value, trimmed: "0.5", "\"campbell\"", "[0, 20, 0]", or a bare word that --set reads as a string.
struct SweepVariable {
  std::string key;
  std::vector<std::string> values;
};

// One run of a sweep: the value of each variable (TOML text, in the order of the variables) and the
// name of its folder under the sweep's output folder.
struct SweepPoint {
  std::vector<std::string> values;
  std::string name;
};

// The most runs one sweep may plan.
constexpr std::size_t kMaxSweepRuns = 100000;

// Splits "v1,v2,..." at the commas that are outside brackets, braces and quoted strings, so
// "[1,2],[3,4]" is two values; trims spaces and tabs around each. Throws std::invalid_argument for
// an empty value (",," or a trailing comma), unbalanced brackets or an unterminated string.
std::vector<std::string> split_values(const std::string& list);

// Parses "KEY=v1,v2,...". Errors are InputError(`label` + " (--vary)", KEY or the spec, reason).
SweepVariable parse_vary(const std::string& spec, const std::string& label);

// The runs of the sweep, in order: with `zip`, run i takes the i-th value of every variable (the
// lists must have equal lengths); otherwise every combination, the first variable varying slowest.
// Errors (InputError, as above): no variables, a key varied twice, unequal lengths with `zip`,
// a combination listed twice, more than kMaxSweepRuns runs.
std::vector<SweepPoint> plan_sweep(const std::vector<SweepVariable>& variables, bool zip, const std::string& label);

// The --set assignments of one run: "KEY=VALUE" for each variable.
std::vector<std::string> point_overrides(const std::vector<SweepVariable>& variables, const SweepPoint& point);

// "KEY=VALUE KEY2=VALUE2" with the TOML texts, for messages.
std::string describe_point(const std::vector<SweepVariable>& variables, const SweepPoint& point);

// A value as a table cell: the content of a TOML string ("\"rough\"" -> "rough"), else the text as given.
std::string display_value(const std::string& toml_text);

// `text` reduced to letters, digits and . _ + - : every run of other characters (spaces, quotes,
// brackets, commas, slashes, non-ASCII bytes) becomes one '_', and '_' at either end is dropped.
std::string safe_name(const std::string& text);

}  // namespace grainflow::run
