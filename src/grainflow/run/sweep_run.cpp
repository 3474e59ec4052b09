#include "grainflow/run/sweep_run.hpp"

#include <fcntl.h>
#include <sched.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <thread>

#include "grainflow/run/sweep_plan.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/flat_json_reader.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/parallel/communicator.hpp"

extern char** environ;

namespace grainflow::run {

namespace fs = std::filesystem;

namespace {

// What happened to one run.
struct RunResult {
  int status = -1;       // exit status; 128 + signal when killed; -1 not run (yet)
  double seconds = 0.0;  // wall-clock time of the child
  std::string reason;    // for a failure: the last line the run wrote, or why it did not start
};

int usable_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? static_cast<int>(n) : 1;
}

int resolve_jobs(const SweepOptions& options, int threads) {
  if (options.jobs > 0) return options.jobs;
  if (parallel::Communicator::world().size() > 1) return 1;  // mpirun placed one rank per slot
  if (const char* env = std::getenv("GRAINFLOW_JOBS"); env && *env) {
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(env, &end, 10);
    if (errno || *end || n < 1 || n > 4096)
      throw InputError("$GRAINFLOW_JOBS", "", "expected a whole number from 1 to 4096, got '" + std::string(env) + "'");
    return static_cast<int>(n);
  }
  return std::max(1, usable_cores() / threads);
}

// The grainflow executable to run the children with: this very program.
std::string executable_path(const std::vector<std::string>& command) {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (!error && fs::exists(self, error)) return self.string();
  return command.empty() ? std::string("grainflow") : command.front();
}

std::string csv_field(const std::string& text) {
  const bool quote = text.find_first_of(",\"\n\r") != std::string::npos ||
                     (!text.empty() && (text.front() == ' ' || text.back() == ' ' || text.front() == '#'));
  if (!quote) return text;
  std::string out = "\"";
  for (const char ch : text) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

std::string json_list(const std::vector<std::string>& items) {
  std::string out = "[";
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i) out += ", ";
    out += io::json_quote(items[i]);
  }
  return out + "]";
}

// The last non-empty line of a run's log (its error message), shortened.
std::string last_line(const fs::path& log) {
  std::ifstream in(log);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  if (const auto cr = last.rfind('\r'); cr != std::string::npos) last = last.substr(cr + 1);  // a progress line
  if (last.size() > 300) last = last.substr(0, 297) + "...";
  return last;
}

std::string describe_status(int status) {
  if (status > 128 && status < 128 + 65) return "killed by signal " + std::to_string(status - 128);
  return "exit " + std::to_string(status);
}

struct Sweep {
  const SweepOptions& options;
  std::vector<std::string> command;
  std::vector<SweepVariable> variables;
  std::vector<SweepPoint> points;
  std::string output_directory;
  int jobs = 1, threads = 1;
  std::vector<RunResult> results;

  void write_json() const {
    io::write_atomically((fs::path(output_directory) / "sweep.json").string(), [&](std::ostream& out) {
      out << "{\n";
      out << "  \"command\": " << json_list(command) << ",\n";
      out << "  \"case\": " << io::json_quote(options.case_path) << ",\n";
      out << "  \"output\": " << io::json_quote(output_directory) << ",\n";
      out << "  \"mode\": " << (options.zip ? "\"zip\"" : "\"product\"") << ",\n";
      out << "  \"vary\": [";
      for (std::size_t v = 0; v < variables.size(); ++v)
        out << (v ? ",\n" : "\n") << "    {\"key\": " << io::json_quote(variables[v].key)
            << ", \"values\": " << json_list(variables[v].values) << "}";
      out << "\n  ],\n";
      out << "  \"set\": " << json_list(options.overrides) << ",\n";
      out << "  \"jobs\": " << jobs << ",\n";
      out << "  \"threads\": " << threads << ",\n";
      out << "  \"runs\": [";
      for (std::size_t r = 0; r < points.size(); ++r) {
        out << (r ? ",\n" : "\n") << "    {\"run\": " << io::json_quote(points[r].name)
            << ", \"values\": " << json_list(points[r].values) << ", \"status\": ";
        if (results[r].status < 0) out << "null";
        else out << results[r].status;
        out << "}";
      }
      out << "\n  ]\n}\n";
    });
  }

  void write_csv() const {
    // The summaries' scalar fields, union over runs in order of first appearance.
    std::vector<std::map<std::string, std::string>> fields(points.size());
    std::vector<std::string> columns;
    std::set<std::string> known;
    for (std::size_t r = 0; r < points.size(); ++r) {
      const fs::path summary = fs::path(output_directory) / points[r].name / "summary.json";
      std::error_code error;
      if (!fs::exists(summary, error)) continue;
      try {
        for (const auto& [key, value] : io::read_flat_json_file(summary.string())) {
          fields[r][key] = value.text;
          if (known.insert(key).second) columns.push_back(key);
        }
      } catch (const io::JsonParseError& e) {
        std::cerr << "grainflow: sweep: " << e.what() << " (its fields are left empty in sweep.csv)\n";
      }
    }
    // Header: the varied keys, run, status, then the summary fields (renamed summary.<field> where
    // one would repeat a column before it).
    std::vector<std::string> header;
    std::set<std::string> taken;
    for (const auto& variable : variables) {
      header.push_back(variable.key);
      taken.insert(variable.key);
    }
    header.push_back("run");
    header.push_back("status");
    taken.insert({"run", "status"});
    for (const auto& column : columns) header.push_back(taken.count(column) ? "summary." + column : column);

    io::write_atomically((fs::path(output_directory) / "sweep.csv").string(), [&](std::ostream& out) {
      out << "# grainflow sweep of " << options.case_path << ": " << points.size()
          << " runs; values as given to --vary, then each run's folder, exit status and summary.json fields\n";
      out << "# units: the varied keys' as in the case file (docs/CASE_FILES.md), the summary fields' as in "
             "summary.json (docs/OUTPUTS.md); status is the run's exit status\n";
      for (std::size_t c = 0; c < header.size(); ++c) out << (c ? "," : "") << csv_field(header[c]);
      out << "\n";
      for (std::size_t r = 0; r < points.size(); ++r) {
        for (const auto& value : points[r].values) out << csv_field(display_value(value)) << ",";
        out << csv_field(points[r].name) << "," << results[r].status;
        for (const auto& column : columns) {
          const auto it = fields[r].find(column);
          out << "," << (it == fields[r].end() ? std::string() : csv_field(it->second));
        }
        out << "\n";
      }
    });
  }

  // Starts run `r`; returns its pid, or -1 (with the result filled in) when it could not start.
  pid_t start(std::size_t r, const std::string& exe) {
    const fs::path dir = fs::path(output_directory) / points[r].name;
    std::error_code error;
    fs::create_directories(dir, error);
    if (error) {
      results[r].status = 127;
      results[r].reason = "cannot create " + dir.string() + ": " + error.message();
      return -1;
    }
    fs::remove(dir / "summary.json", error);  // a stale one from an earlier sweep must not be read back

    std::vector<std::string> args = {exe,          "run",     options.case_path, "-o",
                                     dir.string(), "--quiet", "--threads",       std::to_string(threads)};
    std::vector<std::string> sets = options.overrides;
    for (auto& assignment : point_overrides(variables, points[r])) sets.push_back(std::move(assignment));
    for (const auto& assignment : sets) {
      args.push_back("--set");
      args.push_back(assignment);
    }
    std::vector<char*> argv;
    for (auto& arg : args) argv.push_back(arg.data());
    argv.push_back(nullptr);

    const std::string log = (dir / "run.log").string();
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t pid = -1;
    const int spawn_error = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), child_environment().data());
    posix_spawn_file_actions_destroy(&actions);
    if (spawn_error != 0) {
      results[r].status = 127;
      results[r].reason = "cannot start " + exe + ": " + std::strerror(spawn_error);
      return -1;
    }
    return pid;
  }

  void report(std::size_t r, std::size_t finished) const {
    if (options.quiet) return;
    const RunResult& result = results[r];
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.3g s", result.seconds);
    const auto& comm = parallel::Communicator::world();
    std::size_t total = 0;
    for (std::size_t q = 0; q < points.size(); ++q) total += mine(q);
    std::cerr << "grainflow sweep: " << (comm.size() > 1 ? "rank " + std::to_string(comm.rank()) + " " : std::string())
              << "[" << finished << "/" << total << "] " << points[r].name << ": "
              << (result.status == 0 ? "ok" : "FAILED (" + describe_status(result.status) + ")") << ", " << seconds;
    if (result.status != 0 && !result.reason.empty()) std::cerr << ": " << result.reason;
    std::cerr << "\n";
  }

  // The children are plain one-rank runs, also when the sweep itself runs under mpirun.
  static std::vector<char*>& child_environment() {
    static std::vector<char*> env = [] {
      std::vector<char*> e;
      for (char** v = environ; *v != nullptr; ++v) e.push_back(*v);
      static char serial[] = "GRAINFLOW_SERIAL=1";
      e.push_back(serial);
      e.push_back(nullptr);
      return e;
    }();
    return env;
  }

  // Under mpirun each rank runs every size-th point from its rank; the results meet on rank 0.
  bool mine(std::size_t r) const {
    const auto& comm = parallel::Communicator::world();
    return static_cast<int>(r % static_cast<std::size_t>(comm.size())) == comm.rank();
  }

  void gather_results() {
    const auto& comm = parallel::Communicator::world();
    if (comm.size() == 1) return;
    std::vector<std::uint8_t> mine_bytes;
    auto put = [&](const void* p, std::size_t n) {
      mine_bytes.insert(mine_bytes.end(), static_cast<const std::uint8_t*>(p), static_cast<const std::uint8_t*>(p) + n);
    };
    for (std::size_t r = 0; r < points.size(); ++r) {
      if (!mine(r)) continue;
      const RunResult& result = results[r];
      const std::uint64_t index = r, length = result.reason.size();
      put(&index, sizeof index);
      put(&result.status, sizeof result.status);
      put(&result.seconds, sizeof result.seconds);
      put(&length, sizeof length);
      put(result.reason.data(), length);
    }
    const auto all = comm.gather(mine_bytes);
    for (const auto& from : all) {
      std::size_t at = 0;
      auto get = [&](void* p, std::size_t n) {
        std::memcpy(p, from.data() + at, n);
        at += n;
      };
      while (at < from.size()) {
        std::uint64_t index = 0, length = 0;
        get(&index, sizeof index);
        RunResult& result = results[index];
        get(&result.status, sizeof result.status);
        get(&result.seconds, sizeof result.seconds);
        get(&length, sizeof length);
        result.reason.assign(reinterpret_cast<const char*>(from.data() + at), length);
        at += length;
      }
    }
  }

  void run_all() {
    const std::string exe = executable_path(command);
    using clock = std::chrono::steady_clock;
    std::map<pid_t, std::pair<std::size_t, clock::time_point>> running;
    std::size_t next = 0, finished = 0;
    while (next < points.size() || !running.empty()) {
      while (next < points.size() && running.size() < static_cast<std::size_t>(jobs)) {
        const std::size_t r = next++;
        if (!mine(r)) continue;
        const auto started = clock::now();
        const pid_t pid = start(r, exe);
        if (pid < 0) {
          report(r, ++finished);
          continue;
        }
        running[pid] = {r, started};
      }
      if (running.empty()) continue;
      int wait_status = 0;
      const pid_t pid = ::waitpid(-1, &wait_status, 0);
      if (pid < 0) {
        if (errno == EINTR) continue;
        throw RunError(std::string("waiting for the runs failed: ") + std::strerror(errno));
      }
      const auto it = running.find(pid);
      if (it == running.end()) continue;  // not one of ours
      const auto [r, started] = it->second;
      running.erase(it);
      RunResult& result = results[r];
      result.seconds = std::chrono::duration<double>(clock::now() - started).count();
      if (WIFEXITED(wait_status)) result.status = WEXITSTATUS(wait_status);
      else if (WIFSIGNALED(wait_status)) result.status = 128 + WTERMSIG(wait_status);
      else result.status = 1;
      const fs::path log = fs::path(output_directory) / points[r].name / "run.log";
      std::error_code error;
      if (result.status != 0) result.reason = last_line(log);
      if (fs::file_size(log, error) == 0 && !error) fs::remove(log, error);  // a quiet run says nothing
      report(r, ++finished);
    }
  }
};

}  // namespace

int run_sweep(const SweepOptions& options, const std::vector<std::string>& command) {
  Sweep sweep{options, command, {}, {}, {}, 1, 1, {}};
  for (const auto& spec : options.vary) sweep.variables.push_back(parse_vary(spec, options.case_path));
  sweep.points = plan_sweep(sweep.variables, options.zip, options.case_path);
  for (const auto& assignment : options.overrides) {
    const std::string key = assignment.substr(0, assignment.find('='));
    for (const auto& variable : sweep.variables)
      if (variable.key == key)
        throw InputError(options.case_path + " (--vary)", key, "is given by both --set and --vary");
  }
  sweep.threads = options.threads > 0 ? options.threads : 1;
  sweep.jobs = resolve_jobs(options, sweep.threads);
  sweep.output_directory = options.output_directory.empty()
                               ? (fs::path("runs") / (fs::path(options.case_path).stem().string() + "_sweep")).string()
                               : options.output_directory;

  // Every combination is loaded and validated before anything is written.
  std::size_t invalid = 0;
  constexpr std::size_t kShown = 10;
  for (const auto& point : sweep.points) {
    std::vector<std::string> overrides = options.overrides;
    for (auto& assignment : point_overrides(sweep.variables, point)) overrides.push_back(std::move(assignment));
    try {
      (void)load_case(options.case_path, overrides);
    } catch (const InputError& e) {
      if (++invalid <= kShown)
        std::cerr << "grainflow: invalid input: " << e.what() << " (sweep run "
                  << describe_point(sweep.variables, point) << ")\n";
    }
  }
  if (invalid > 0) {
    if (invalid > kShown) std::cerr << "grainflow: ... and " << invalid - kShown << " more invalid combinations\n";
    std::cerr << "grainflow: sweep: " << invalid << " of " << sweep.points.size()
              << " combinations are invalid; nothing was run\n";
    return 2;
  }
  std::error_code error;
  if (fs::exists(sweep.output_directory, error) && !fs::is_directory(sweep.output_directory, error))
    throw InputError(sweep.output_directory, "", "the output folder exists and is not a folder");

  const auto& comm = parallel::Communicator::world();
  fs::create_directories(sweep.output_directory);
  sweep.results.assign(sweep.points.size(), RunResult{});
  if (comm.root()) sweep.write_json();  // the plan, so an interrupted sweep still says what it was
  if (!options.quiet && comm.root())
    std::cerr << "grainflow sweep: " << sweep.points.size() << " runs of " << options.case_path << " into "
              << sweep.output_directory << ", " << sweep.jobs << " at a time"
              << (comm.size() > 1 ? " on each of " + std::to_string(comm.size()) + " MPI ranks" : std::string())
              << "\n";
  sweep.run_all();
  sweep.gather_results();
  if (!comm.root()) return 0;  // rank 0 writes the tables and reports
  sweep.write_json();
  sweep.write_csv();

  std::vector<std::size_t> failed;
  for (std::size_t r = 0; r < sweep.points.size(); ++r)
    if (sweep.results[r].status != 0) failed.push_back(r);
  const std::string csv = (fs::path(sweep.output_directory) / "sweep.csv").string();
  if (failed.empty()) {
    if (!options.quiet)
      std::cerr << "grainflow sweep: all " << sweep.points.size() << " runs succeeded: " << csv << "\n";
    return 0;
  }
  std::cerr << "grainflow: sweep: " << failed.size() << " of " << sweep.points.size() << " runs failed (" << csv
            << "):\n";
  for (const std::size_t r : failed) {
    std::cerr << "  " << sweep.points[r].name << ": " << describe_status(sweep.results[r].status);
    if (!sweep.results[r].reason.empty()) std::cerr << ": " << sweep.results[r].reason;
    std::cerr << "\n";
  }
  return 1;
}

}  // namespace grainflow::run
