#include "grainflow/config/particle_csv.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>

#include "grainflow/core/error.hpp"

namespace grainflow::io {
namespace {

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string_view field =
        line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    while (!field.empty() && (field.front() == ' ' || field.front() == '\t')) field.remove_prefix(1);
    while (!field.empty() && (field.back() == ' ' || field.back() == '\t' || field.back() == '\r'))
      field.remove_suffix(1);
    fields.push_back(field);
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return fields;
}

}  // namespace

std::vector<InitialParticle> read_particle_csv(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error))  // not a device or a pipe that never ends
    throw InputError(path, "",
                     std::filesystem::exists(path, error) ? "is not a regular file" : "cannot open the particle file");
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the particle file");
  return read_particle_csv(in, path);
}

std::vector<InitialParticle> read_particle_csv(std::istream& in, const std::string& path) {
  // `id` is accepted (and ignored) so that a run's final_state.csv can start another run.
  static const std::array<const char*, 12> known = {"id", "species", "x",  "y",  "z",  "vx",
                                                    "vy", "vz",      "wx", "wy", "wz", "diameter"};
  std::map<std::string, int> column;  // name -> field index
  std::vector<InitialParticle> out;
  std::string line;
  long line_number = 0;
  std::size_t header_fields = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty() || line[0] == '#' || line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = split(line);
    const std::string where = "line " + std::to_string(line_number);
    if (column.empty()) {
      for (std::size_t i = 0; i < fields.size(); ++i) {
        const std::string name(fields[i]);
        bool ok = false;
        for (const char* k : known) ok = ok || name == k;
        if (!ok) throw InputError(path, where, "unknown column '" + name + "'");
        if (column.count(name)) throw InputError(path, where, "column '" + name + "' appears twice");
        column[name] = static_cast<int>(i);
      }
      for (const char* required : {"species", "x", "y", "z", "vx", "vy", "vz"})
        if (!column.count(required)) throw InputError(path, where, std::string("missing column '") + required + "'");
      header_fields = fields.size();
      continue;
    }
    if (fields.size() != header_fields)
      throw InputError(path, where,
                       "expected " + std::to_string(header_fields) + " fields, found " + std::to_string(fields.size()));
    auto number = [&](const char* name, double fallback) {
      auto it = column.find(name);
      if (it == column.end()) return fallback;
      const std::string_view text = fields[it->second];
      double value = 0.0;
      const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
      if (result.ec != std::errc() || result.ptr != text.data() + text.size() || !std::isfinite(value))
        throw InputError(path, where,
                         std::string("column '") + name + "': '" + std::string(text) + "' is not a finite number");
      return value;
    };
    InitialParticle p;
    p.species = std::string(fields[column["species"]]);
    if (p.species.empty()) throw InputError(path, where, "empty species name");
    p.position = {number("x", 0), number("y", 0), number("z", 0)};
    p.velocity = {number("vx", 0), number("vy", 0), number("vz", 0)};
    p.angular_velocity = {number("wx", 0), number("wy", 0), number("wz", 0)};
    p.diameter = number("diameter", 0.0);
    if (column.count("diameter") && !(p.diameter > 0.0)) throw InputError(path, where, "diameter must be positive");
    out.push_back(p);
  }
  if (column.empty()) throw InputError(path, "", "no header row (species,x,y,z,vx,vy,vz,...)");
  return out;
}

}  // namespace grainflow::io
