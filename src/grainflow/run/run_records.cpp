#include "grainflow/run/run_records.hpp"
#include "grainflow/parallel/communicator.hpp"

#include <chrono>
#include <ctime>
#include <filesystem>

#include "grainflow/run/machine_info.hpp"
#include "grainflow/core/build_info.hpp"
#include "grainflow/config/case_writer.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/core/version.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/json_writer.hpp"

namespace grainflow::run {
namespace {

// ISO 8601 in UTC, to the second: comparable across machines and time zones.
std::string utc_time(wall_clock::time_point t) {
  const std::time_t seconds = wall_clock::to_time_t(t);
  std::tm parts{};
  ::gmtime_r(&seconds, &parts);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &parts);
  return text;
}

}  // namespace

void write_run_log(const std::string& dir, const CaseConfig& c, const RunOptions& options,
                   const std::vector<std::string>& command_line, wall_clock::time_point start,
                   wall_clock::time_point end, int exit_status) {
  io::JsonObject log;
  log.string("version", kVersion);
  log.string("git_commit", kGitCommit);
  log.string("hostname", host_name());
  log.string("cpu_model", cpu_model());
  log.integer("cpu_cores", logical_cores());
  log.integer("threads", options.threads);
  log.strings("command_line", command_line);
  log.string("case", c.path);
  log.strings("case_overrides", c.overrides);
  log.string("resolved_case", "resolved_case.toml");
  log.string("start_time", utc_time(start));
  log.string("end_time", utc_time(end));
  log.number("wall_seconds", std::chrono::duration<double>(end - start).count());
  log.integer("exit_status", exit_status);
  io::write_atomically(dir + "/run_log.json", [&](std::ostream& out) { log.write(out); });
}

int run_with_records(const CaseConfig& c, const RunOptions& options, const std::vector<std::string>& command_line,
                     const std::function<int()>& run) {
  if (!parallel::Communicator::world().root()) return run();  // MPI: rank 0 keeps the records
  const std::string& dir = options.output_directory;
  const bool existed = std::filesystem::exists(dir);
  std::filesystem::create_directories(dir);
  io::write_atomically(dir + "/resolved_case.toml", [&](std::ostream& out) { out << write_case_toml(c); });
  const auto start = wall_clock::now();
  int status = 1;
  try {
    status = run();
  } catch (const InputError&) {
    // Input refused before the run began (a checkpoint that does not fit, say): nothing written.
    std::error_code ignored;
    std::filesystem::remove(dir + "/resolved_case.toml", ignored);
    if (!existed) std::filesystem::remove(dir, ignored);  // only when empty
    throw;
  } catch (...) {
    write_run_log(dir, c, options, command_line, start, wall_clock::now(), 1);
    throw;
  }
  write_run_log(dir, c, options, command_line, start, wall_clock::now(), status);
  return status;
}

}  // namespace grainflow::run
