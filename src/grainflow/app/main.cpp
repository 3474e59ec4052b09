// The `grainflow` command line (INTERFACE.md): run, check, plot, analyze, sweep, calibrate, theory, cases, --version.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <new>
#include <string>
#include <unistd.h>
#include <vector>

#include "grainflow/core/error.hpp"
#include "grainflow/core/version.hpp"
#include "grainflow/run/calibration_run.hpp"
#include "grainflow/run/check_report.hpp"
#include "grainflow/run/constitutive_table.hpp"
#include "grainflow/run/process_start.hpp"
#include "grainflow/run/run_command.hpp"
#include "grainflow/run/sweep_run.hpp"
#include "grainflow/run/theory_report.hpp"
#include "grainflow/run/trajectory_analysis.hpp"

namespace fs = std::filesystem;
using namespace grainflow;

namespace {

// The installation's root (where cases/ and tools/ live): the executable sits in build/<preset>/.
fs::path project_root() {
  std::error_code error;
  const fs::path exe = fs::read_symlink("/proc/self/exe", error);
  if (!error) {
    for (fs::path dir = exe.parent_path(); !dir.empty() && dir != dir.root_path(); dir = dir.parent_path())
      if (fs::exists(dir / "cases") && fs::exists(dir / "tools")) return dir;
  }
  return fs::current_path();
}

int list_cases() {
  const fs::path root = project_root() / "cases";
  std::vector<fs::path> files;
  for (const auto& entry : fs::recursive_directory_iterator(root))
    if (entry.path().extension() == ".toml") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    std::ifstream in(file);
    std::string first;
    std::getline(in, first);
    if (first.rfind("#", 0) == 0) first = first.substr(first.find_first_not_of("# "));
    std::cout << fs::relative(file, root.parent_path()).string() << "\n    " << first << "\n";
  }
  return 0;
}

int plot(const std::string& directory) {
  const fs::path script = project_root() / "tools" / "plot_run.py";
  const std::string command = "/usr/bin/python3 '" + script.string() + "' '" + directory + "'";
  const int status = std::system(command.c_str());
  return status == 0 ? 0 : 1;
}

// What the subcommands were given: CLI11 writes into these while it parses. `run` and `check` share
// the case and its --set overrides.
struct Arguments {
  run::RunCommand run_command;
  std::string plot_directory;
  std::string analyze_directory;
  run::AnalyzeOptions analyze;
  std::vector<int> analyze_strips;
  run::SweepOptions sweep;
  run::CalibrationOptions calibrate;
  double calibrate_duration = 0.0, calibrate_start_k1 = 0.0;
  CLI::Option* calibrate_duration_option = nullptr;  // given or not: the case's run.duration otherwise
  CLI::Option* calibrate_start_option = nullptr;     // given or not: K1_H / 100 otherwise
  run::TheoryOptions theory;
  run::ConstitutiveOptions constitutive;
};

void add_run(CLI::App& app, Arguments& a) {
  auto* run = app.add_subcommand("run", "run a case and write its output folder");
  run->add_option("case", a.run_command.case_path, "case file (TOML)")->required();
  run->add_option("-o,--output", a.run_command.output_directory, "output folder (default: runs/<case name>)");
  run->add_option("--set", a.run_command.overrides, "override a case key: --set contact.k1=2e6")
      ->type_name("KEY=VALUE");
  run->add_option("--threads", a.run_command.threads, "OpenMP threads (default 1)")->check(CLI::Range(1, 1024));
  run->add_flag("--quiet", a.run_command.quiet, "no progress line");
  run->add_option("--restart", a.run_command.restart,
                  "continue from a checkpoint.h5 of this case (outputs go to its folder unless -o is given)");
}

void add_check(CLI::App& app, Arguments& a) {
  auto* check = app.add_subcommand("check", "validate a case and print its derived quantities; runs nothing");
  check->add_option("case", a.run_command.case_path, "case file (TOML)")->required();
  check->add_option("--set", a.run_command.overrides, "override a case key")->type_name("KEY=VALUE");
}

void add_plot(CLI::App& app, Arguments& a) {
  auto* plot_cmd = app.add_subcommand("plot", "PNG figures of a run or sweep folder");
  plot_cmd->add_option("outdir", a.plot_directory, "output folder of a run")->required();
}

// grainflow analyze: correlations and diffusion from a run's trajectory.h5 (run/trajectory_analysis.hpp).
void add_analyze(CLI::App& app, Arguments& a) {
  auto* analyze = app.add_subcommand("analyze", "correlation functions and diffusion coefficients of a finished run");
  analyze->add_option("outdir", a.analyze_directory, "output folder of a run with trajectory.h5")->required();
  analyze->add_option("--max-lag", a.analyze.max_lag, "longest lag in samples (default: the case's trajectory.max_lag)")
      ->check(CLI::Range(2LL, 1000000000LL));
  analyze->add_option("--groups", a.analyze.groups, "independent particle groups for the error bars (default 8)")
      ->check(CLI::Range(1, 1000000));
  analyze
      ->add_option("--strips", a.analyze_strips,
                   "edmd: count only particles in strips FIRST..LAST (from the bottom wall; default all)")
      ->expected(2)
      ->check(CLI::NonNegativeNumber);
}

// grainflow sweep: the case at many values of some keys, runs in parallel (run/sweep_run.hpp).
void add_sweep(CLI::App& app, Arguments& a) {
  auto* sweep = app.add_subcommand("sweep", "run a case at many values of some keys, as parallel processes");
  sweep->add_option("case", a.sweep.case_path, "case file (TOML)")->required();
  sweep->add_option("--vary", a.sweep.vary, "a key and its values: --vary collision.restitution=0.5,0.7")
      ->type_name("KEY=V1,V2,...")
      ->required()
      ->allow_extra_args(false);
  sweep->add_flag("--zip", a.sweep.zip, "take the --vary lists element by element, not every combination");
  sweep->add_option("-o,--output", a.sweep.output_directory, "output folder (default: runs/<case name>_sweep)");
  sweep->add_option("--jobs", a.sweep.jobs, "runs at a time (default: $GRAINFLOW_JOBS, else cores / threads)")
      ->check(CLI::Range(1, 4096));
  sweep->add_option("--set", a.sweep.overrides, "override a case key in every run")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  sweep->add_option("--threads", a.sweep.threads, "OpenMP threads of each run (default 1)")->check(CLI::Range(1, 1024));
  sweep->add_flag("--quiet", a.sweep.quiet, "no progress lines");
}

// grainflow calibrate: K1 by Lan's maximum-overlap procedure (run/calibration_run.hpp).
void add_calibrate(CLI::App& app, Arguments& a) {
  auto* calibrate =
      app.add_subcommand("calibrate", "find the smallest K1 that keeps the max overlap <= 1% d (Lan 4.1.3)");
  calibrate->add_option("case", a.calibrate.case_path, "case file (TOML, DEM, a law calibrate can vary)")->required();
  calibrate->add_option("-o,--output", a.calibrate.output_directory,
                        "output folder (default: runs/calibrate_<case name>)");
  a.calibrate_duration_option = calibrate->add_option("--duration", a.calibrate_duration,
                                                      "simulated s per trial (default: the case's run.duration)");
  calibrate->add_option("--factor", a.calibrate.factor, "K1 changes by this factor between trials (default 1.25)");
  calibrate->add_option("--limit", a.calibrate.limit, "largest acceptable max overlap / d (default 0.01)");
  a.calibrate_start_option = calibrate->add_option("--start-k1", a.calibrate_start_k1,
                                                   "first trial K1 in N/m (default: Hertz-equivalent K1 / 100)");
  calibrate->add_option("--max-trials", a.calibrate.max_trials, "most trials to run (default 20)");
  calibrate->add_option("--set", a.calibrate.overrides, "override a case key in every trial")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  calibrate->add_option("--threads", a.calibrate.threads, "OpenMP threads (default 1)")->check(CLI::Range(1, 1024));
  calibrate->add_flag("--quiet", a.calibrate.quiet, "no progress line during the trials");
}

// grainflow theory: steady kinetic-theory profiles of a vibrated bed (run/theory_report.hpp).
void add_theory(CLI::App& app, Arguments& a) {
  auto* theory = app.add_subcommand("theory", "kinetic-theory profiles of a vibrated bed for a case or a run's folder");
  theory->add_option("input", a.theory.input, "case file (TOML), or a run's output folder")->required();
  theory->add_option(
      "-o,--output", a.theory.output,
      "CSV file (default: kinetic_theory.csv here; OUTDIR/analysis/kinetic_theory.csv for a run folder)");
  theory->add_option("--set", a.theory.overrides, "override a case key")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  theory->add_option("--g0", a.theory.contact_value, "radial distribution at contact (default torquato)")
      ->check(CLI::IsMember({"torquato", "carnahan_starling"}));
}

// grainflow constitutive: chi(nu), f_s(nu), f_N(nu) over strips and runs (run/constitutive_table.hpp).
void add_constitutive(CLI::App& app, Arguments& a) {
  auto* constitutive = app.add_subcommand(
      "constitutive", "collect the event-driven runs' constitutive.csv (chi, f_s, f_N per strip) into one table");
  constitutive->add_option("folders", a.constitutive.folders, "run or sweep folders, searched recursively")->required();
  constitutive->add_option("-o,--output", a.constitutive.output,
                           "CSV file (default: constitutive_table.csv in the first folder)");
}

// The one subcommand given, run; its exit status.
int dispatch(const CLI::App& app, Arguments& a, const std::vector<std::string>& command_line) {
  if (app.got_subcommand("cases")) return list_cases();
  if (app.got_subcommand("plot")) return plot(a.plot_directory);
  if (app.got_subcommand("analyze")) {
    if (a.analyze_strips.size() == 2) {
      a.analyze.first_strip = a.analyze_strips[0];
      a.analyze.last_strip = a.analyze_strips[1];
    }
    return run::analyze_run(a.analyze_directory, a.analyze);
  }
  if (app.got_subcommand("theory")) return run::run_theory(a.theory);
  if (app.got_subcommand("constitutive")) return run::collect_constitutive(a.constitutive);
  if (app.got_subcommand("sweep")) return run::run_sweep(a.sweep, command_line);
  if (app.got_subcommand("calibrate")) {
    if (*a.calibrate_duration_option) a.calibrate.duration = a.calibrate_duration;
    if (*a.calibrate_start_option) a.calibrate.start_k1 = a.calibrate_start_k1;
    return run::run_calibration(a.calibrate);
  }
  if (app.got_subcommand("check")) return run::check_case(a.run_command.case_path, a.run_command.overrides, std::cout);
  return run::run_case(a.run_command, command_line);
}

// Runs `command`, turning what it throws into a message on stderr and an exit status: 2 for wrong
// input (a case, a file, a value: nothing was run), 1 for a run that failed (docs/ROBUSTNESS.md).
int with_error_reports(const std::function<int()>& command) {
  try {
    return command();
  } catch (const InputError& e) {
    std::cerr << "grainflow: invalid input: " << e.what() << "\n";
    return 2;
  } catch (const RunError& e) {
    std::cerr << "grainflow: run failed: " << e.what() << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "grainflow: out of memory: the case needs more memory than this machine could give (fewer "
                 "particles, or a smaller domain for the sampled fields); outputs written so far are complete\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "grainflow: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

int main(int argc, char** argv) {
  run::start_process(argc, argv);  // MPI only when started by mpirun
  CLI::App app{"grainflow: particle simulation of granular flows (DEM and event-driven)"};
  app.set_version_flag("--version", std::string("grainflow ") + kVersion);
  app.require_subcommand(1);
  Arguments arguments;
  // The order here is the order of `grainflow --help`.
  add_run(app, arguments);
  add_check(app, arguments);
  add_plot(app, arguments);
  app.add_subcommand("cases", "list the bundled cases");
  add_analyze(app, arguments);
  add_sweep(app, arguments);
  add_calibrate(app, arguments);
  add_theory(app, arguments);
  add_constitutive(app, arguments);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  const std::vector<std::string> command_line(argv, argv + argc);
  return with_error_reports([&] { return dispatch(app, arguments, command_line); });
}
