#include "grainflow/run/run_command.hpp"

#include <filesystem>

#include "grainflow/core/error.hpp"
#include "grainflow/io/checkpoint_file.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/run/dem_run.hpp"
#include "grainflow/run/edmd_run.hpp"
#include "grainflow/run/interrupt.hpp"
#include "grainflow/run/run_records.hpp"
#include "grainflow/run/run_support.hpp"

namespace grainflow::run {

namespace fs = std::filesystem;

std::vector<std::string> restart_overrides(const std::string& checkpoint, const std::string& case_path,
                                           const std::vector<std::string>& overrides) {
  const io::CheckpointHeader header = io::read_checkpoint_header(checkpoint);
  const CaseConfig as_given = load_case(case_path, overrides);
  if (header.engine != as_given.engine.kind || header.dimension != as_given.engine.dimension)
    throw InputError(checkpoint, "",
                     "this checkpoint cannot continue case '" + case_path + "': it is from a " +
                         std::to_string(header.dimension) + "D '" + header.engine + "' run, the case is " +
                         std::to_string(as_given.engine.dimension) + "D '" + as_given.engine.kind + "'");
  std::vector<std::string> all = split_overrides(header.case_overrides);
  all.insert(all.end(), overrides.begin(), overrides.end());
  return all;
}

int run_case(const RunCommand& command, const std::vector<std::string>& command_line) {
  const std::vector<std::string> overrides =
      command.restart.empty() ? command.overrides
                              : restart_overrides(command.restart, command.case_path, command.overrides);
  const CaseConfig c = load_case(command.case_path, overrides);
  RunOptions options;
  options.output_directory = command.output_directory.empty()
                                 ? (fs::path("runs") / fs::path(command.case_path).stem()).string()
                                 : command.output_directory;
  if (command.output_directory.empty() && !command.restart.empty()) {
    const fs::path folder = fs::path(command.restart).parent_path();
    options.output_directory = folder.empty() ? "." : folder.string();
  }
  options.restart = command.restart;
  catch_interrupts();
  options.threads = command.threads;
  options.quiet = command.quiet;
  return run_with_records(c, options, command_line,
                          [&] { return c.engine.kind == "edmd" ? run_edmd(c, options) : run_dem(c, options); });
}

}  // namespace grainflow::run
