#include "grainflow/run/constitutive_table.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "grainflow/core/error.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/flat_json_reader.hpp"

namespace grainflow::run {
namespace {

namespace fs = std::filesystem;

constexpr const char* kRunFile = "constitutive.csv";

struct RunTable {
  std::string run;                    // the run's folder, relative to the folder named
  bool steady = false;                // summary.json's averaged_when_steady
  std::vector<std::string> comments;  // '#' lines
  std::string header;
  std::vector<std::string> rows;
};

// Whether the run's summary says its averages began after the flow had become steady (Campbell's
// convergence check); false when the summary is missing or says otherwise.
bool steady_run(const fs::path& run_folder) {
  const fs::path summary = run_folder / "summary.json";
  if (!fs::exists(summary)) return false;
  try {
    for (const auto& [key, value] : io::read_flat_json_file(summary.string()))
      if (key == "averaged_when_steady") return value.kind == io::FlatJsonValue::Kind::boolean && value.text == "true";
  } catch (const io::JsonParseError& e) {
    throw InputError(summary.string(), "", e.what());
  }
  return false;
}

RunTable read_run_table(const fs::path& file, const std::string& run) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string(), "", "cannot be read");
  RunTable t{run, steady_run(file.parent_path()), {}, {}, {}};
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line.front() == '#') {
      t.comments.push_back(line);
    } else if (t.header.empty()) {
      t.header = line;
    } else {
      t.rows.push_back(line);
    }
  }
  if (t.header.empty()) throw InputError(file.string(), "", "has no column header (an interrupted run?)");
  return t;
}

// The run's label: its folder relative to the folder named (the folder's own name for itself);
// commas would split the CSV field, so they become semicolons.
std::string run_label(const fs::path& folder, const fs::path& run_folder) {
  std::string label = run_folder == folder ? folder.filename().string() : fs::relative(run_folder, folder).string();
  if (label.empty() || label == ".") label = fs::absolute(folder).filename().string();
  std::replace(label.begin(), label.end(), ',', ';');
  return label;
}

std::vector<RunTable> find_tables(const std::string& folder, const fs::path& output) {
  const fs::path root(folder);
  if (!fs::is_directory(root)) throw InputError(folder, "", "is not a folder");
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.is_regular_file() && entry.path().filename() == kRunFile) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<RunTable> tables;
  for (const auto& file : files)
    if (!fs::exists(output) || !fs::equivalent(file, output))
      tables.push_back(read_run_table(file, run_label(root, file.parent_path())));
  if (tables.empty())
    throw InputError(
        folder, "",
        std::string("holds no ") + kRunFile + " (event-driven runs write one when output.collision_stresses is on)");
  return tables;
}

// The index of `name` among the header's comma-separated columns, or -1.
int column_index(const std::string& header, const std::string& name) {
  std::istringstream in(header);
  std::string field;
  for (int i = 0; std::getline(in, field, ','); ++i)
    if (field == name) return i;
  return -1;
}

bool flag_set(const std::string& row, int index) {
  std::istringstream in(row);
  std::string field;
  for (int i = 0; std::getline(in, field, ','); ++i)
    if (i == index) return field == "1";
  return false;
}

}  // namespace

int collect_constitutive(const ConstitutiveOptions& options) {
  if (options.folders.empty()) throw InputError("grainflow constitutive", "", "name at least one folder");
  const fs::path output =
      options.output.empty() ? fs::path(options.folders.front()) / "constitutive_table.csv" : fs::path(options.output);
  std::vector<RunTable> tables;
  for (const auto& folder : options.folders)
    for (auto& t : find_tables(folder, output)) tables.push_back(std::move(t));
  const std::string& header = tables.front().header;
  for (const auto& t : tables)
    if (t.header != header)
      throw InputError(t.run + "/" + kRunFile, "",
                       "its columns differ from " + tables.front().run + "/" + kRunFile +
                           "'s (written by another grainflow version?); rerun it");
  const int usable_chi = column_index(header, "usable_chi"), usable_f = column_index(header, "usable_f");
  long rows = 0, chi_rows = 0, f_rows = 0, steady_runs = 0;
  for (const auto& t : tables) steady_runs += t.steady;
  io::write_atomically(output.string(), [&](std::ostream& out) {
    out << "# Campbell 1982 constitutive functions collected over " << tables.size()
        << " runs (grainflow constitutive)\n";
    for (const auto& comment : tables.front().comments)
      if (comment.rfind("# constitutive functions per strip", 0) != 0)
        out << comment << "\n";  // rho_p, R differ per run
    out << "# steady: 1 when the run's averages began after its kinetic energy had become steady "
           "(summary.json averaged_when_steady, Campbell's section 2.5); figures use those runs only\n";
    out << "run,steady," << header << "\n";
    for (const auto& t : tables)
      for (const auto& row : t.rows) {
        out << t.run << "," << (t.steady ? 1 : 0) << "," << row << "\n";
        ++rows;
        chi_rows += t.steady && flag_set(row, usable_chi);
        f_rows += t.steady && flag_set(row, usable_f);
      }
  });
  std::cout << "wrote " << output.string() << ": " << rows << " strips from " << tables.size() << " runs, "
            << steady_runs << " of them averaged when steady; their strips usable for chi: " << chi_rows
            << ", for f_s and f_N: " << f_rows << "\n";
  return 0;
}

}  // namespace grainflow::run
