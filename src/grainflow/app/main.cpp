// The `grainflow` command line (INTERFACE.md): run, check, plot, analyze, sweep, calibrate, theory, cases, --version.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <unistd.h>

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

}  // namespace

int main(int argc, char** argv) {
  run::start_process(argc, argv);  // MPI only when started by mpirun
  CLI::App app{"grainflow: particle simulation of granular flows (DEM and event-driven)"};
  app.set_version_flag("--version", std::string("grainflow ") + kVersion);
  app.require_subcommand(1);

  std::string plot_dir;
  run::RunCommand run_command;  // `check` shares the case and its --set overrides

  auto* run = app.add_subcommand("run", "run a case and write its output folder");
  run->add_option("case", run_command.case_path, "case file (TOML)")->required();
  run->add_option("-o,--output", run_command.output_directory, "output folder (default: runs/<case name>)");
  run->add_option("--set", run_command.overrides, "override a case key: --set contact.k1=2e6")->type_name("KEY=VALUE");
  run->add_option("--threads", run_command.threads, "OpenMP threads (default 1)")->check(CLI::Range(1, 1024));
  run->add_flag("--quiet", run_command.quiet, "no progress line");
  run->add_option("--restart", run_command.restart,
                  "continue from a checkpoint.h5 of this case (outputs go to its folder unless -o is given)");

  auto* check = app.add_subcommand("check", "validate a case and print its derived quantities; runs nothing");
  check->add_option("case", run_command.case_path, "case file (TOML)")->required();
  check->add_option("--set", run_command.overrides, "override a case key")->type_name("KEY=VALUE");

  auto* plot_cmd = app.add_subcommand("plot", "PNG figures of a run or sweep folder");
  plot_cmd->add_option("outdir", plot_dir, "output folder of a run")->required();

  app.add_subcommand("cases", "list the bundled cases");

  // grainflow analyze: correlations and diffusion from a run's trajectory.h5 (run/trajectory_analysis.hpp).
  std::string analyze_dir;
  run::AnalyzeOptions analyze_options;
  auto* analyze = app.add_subcommand("analyze", "correlation functions and diffusion coefficients of a finished run");
  analyze->add_option("outdir", analyze_dir, "output folder of a run with trajectory.h5")->required();
  analyze->add_option("--max-lag", analyze_options.max_lag, "longest lag in samples (default: the case's trajectory.max_lag)")
      ->check(CLI::Range(2LL, 1000000000LL));
  analyze->add_option("--groups", analyze_options.groups, "independent particle groups for the error bars (default 8)")
      ->check(CLI::Range(1, 1000000));
  std::vector<int> analyze_strips;
  analyze->add_option("--strips", analyze_strips,
                      "edmd: count only particles in strips FIRST..LAST (from the bottom wall; default all)")
      ->expected(2)
      ->check(CLI::NonNegativeNumber);

  // grainflow sweep: the case at many values of some keys, runs in parallel (run/sweep_run.hpp).
  run::SweepOptions sweep_options;
  auto* sweep = app.add_subcommand("sweep", "run a case at many values of some keys, as parallel processes");
  sweep->add_option("case", sweep_options.case_path, "case file (TOML)")->required();
  sweep->add_option("--vary", sweep_options.vary, "a key and its values: --vary collision.restitution=0.5,0.7")
      ->type_name("KEY=V1,V2,...")->required()->allow_extra_args(false);
  sweep->add_flag("--zip", sweep_options.zip, "take the --vary lists element by element, not every combination");
  sweep->add_option("-o,--output", sweep_options.output_directory, "output folder (default: runs/<case name>_sweep)");
  sweep->add_option("--jobs", sweep_options.jobs, "runs at a time (default: $GRAINFLOW_JOBS, else cores / threads)")
      ->check(CLI::Range(1, 4096));
  sweep->add_option("--set", sweep_options.overrides, "override a case key in every run")
      ->type_name("KEY=VALUE")->allow_extra_args(false);
  sweep->add_option("--threads", sweep_options.threads, "OpenMP threads of each run (default 1)")->check(CLI::Range(1, 1024));
  sweep->add_flag("--quiet", sweep_options.quiet, "no progress lines");

  // grainflow calibrate: K1 by Lan's maximum-overlap procedure (run/calibration_run.hpp).
  run::CalibrationOptions calibrate_options;
  double calibrate_duration = 0.0, calibrate_start_k1 = 0.0;
  auto* calibrate =
      app.add_subcommand("calibrate", "find the smallest K1 that keeps the max overlap <= 1% d (Lan 4.1.3)");
  calibrate->add_option("case", calibrate_options.case_path, "case file (TOML, DEM, a law calibrate can vary)")->required();
  calibrate->add_option("-o,--output", calibrate_options.output_directory,
                        "output folder (default: runs/calibrate_<case name>)");
  auto* duration_option =
      calibrate->add_option("--duration", calibrate_duration, "simulated s per trial (default: the case's run.duration)");
  calibrate->add_option("--factor", calibrate_options.factor, "K1 changes by this factor between trials (default 1.25)");
  calibrate->add_option("--limit", calibrate_options.limit, "largest acceptable max overlap / d (default 0.01)");
  auto* start_option =
      calibrate->add_option("--start-k1", calibrate_start_k1, "first trial K1 in N/m (default: Hertz-equivalent K1 / 100)");
  calibrate->add_option("--max-trials", calibrate_options.max_trials, "most trials to run (default 20)");
  calibrate->add_option("--set", calibrate_options.overrides, "override a case key in every trial")
      ->type_name("KEY=VALUE")->allow_extra_args(false);
  calibrate->add_option("--threads", calibrate_options.threads, "OpenMP threads (default 1)")->check(CLI::Range(1, 1024));
  calibrate->add_flag("--quiet", calibrate_options.quiet, "no progress line during the trials");
  // grainflow theory: steady kinetic-theory profiles of a vibrated bed (run/theory_report.hpp).
  run::TheoryOptions theory_options;
  auto* theory = app.add_subcommand("theory", "kinetic-theory profiles of a vibrated bed for a case or a run's folder");
  theory->add_option("input", theory_options.input, "case file (TOML), or a run's output folder")->required();
  theory->add_option("-o,--output", theory_options.output,
                     "CSV file (default: kinetic_theory.csv here; OUTDIR/analysis/kinetic_theory.csv for a run folder)");
  theory->add_option("--set", theory_options.overrides, "override a case key")->type_name("KEY=VALUE")->allow_extra_args(false);
  theory->add_option("--g0", theory_options.contact_value, "radial distribution at contact (default torquato)")
      ->check(CLI::IsMember({"torquato", "carnahan_starling"}));

  // grainflow constitutive: chi(nu), f_s(nu), f_N(nu) over strips and runs (run/constitutive_table.hpp).
  run::ConstitutiveOptions constitutive_options;
  auto* constitutive = app.add_subcommand(
      "constitutive", "collect the event-driven runs' constitutive.csv (chi, f_s, f_N per strip) into one table");
  constitutive->add_option("folders", constitutive_options.folders, "run or sweep folders, searched recursively")->required();
  constitutive->add_option("-o,--output", constitutive_options.output,
                           "CSV file (default: constitutive_table.csv in the first folder)");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }

  try {
    if (app.got_subcommand("cases")) return list_cases();
    if (app.got_subcommand("plot")) return plot(plot_dir);
    if (app.got_subcommand("analyze")) {
      if (analyze_strips.size() == 2) {
        analyze_options.first_strip = analyze_strips[0];
        analyze_options.last_strip = analyze_strips[1];
      }
      return run::analyze_run(analyze_dir, analyze_options);
    }
    if (app.got_subcommand("theory")) return run::run_theory(theory_options);
    if (app.got_subcommand("constitutive")) return run::collect_constitutive(constitutive_options);
    if (app.got_subcommand("sweep")) return run::run_sweep(sweep_options, std::vector<std::string>(argv, argv + argc));
    if (app.got_subcommand("calibrate")) {
      if (*duration_option) calibrate_options.duration = calibrate_duration;
      if (*start_option) calibrate_options.start_k1 = calibrate_start_k1;
      return run::run_calibration(calibrate_options);
    }
    if (app.got_subcommand("check")) return run::check_case(run_command.case_path, run_command.overrides, std::cout);
    return run::run_case(run_command, std::vector<std::string>(argv, argv + argc));
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
