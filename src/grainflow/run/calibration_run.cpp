#include "grainflow/run/calibration_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>
#include <limits>
#include <optional>

#include "grainflow/run/dem_run.hpp"
#include "grainflow/run/stiffness_search.hpp"
#include "grainflow/run/case_loader.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/core/version.hpp"
#include "grainflow/dem/contact_law_registry.hpp"
#include "grainflow/dem/derived_quantities.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/flat_json_reader.hpp"
#include "grainflow/io/json_writer.hpp"
#include "grainflow/observe/zone_series_observer.hpp"

namespace grainflow::run {
namespace {

namespace fs = std::filesystem;

constexpr double kNone = std::numeric_limits<double>::quiet_NaN();  // written as null

// The shortest text that reads back as the same double (for --set values and the CSV file).
std::string exact(double value) { return fmt::format("{}", value); }

// What one trial measured, from its summary.json.
struct TrialRecord {
  double k1 = 0.0, time_step = 0.0, max_overlap = 0.0, simulated_time = 0.0, wall_seconds = 0.0;
  bool halted = false, passed = false;
  std::string folder;
};

void check_options(const CalibrationOptions& o) {
  if (!(o.factor > 1.0) || !std::isfinite(o.factor))
    throw InputError("--factor", "", "must be greater than 1 (K1 is multiplied by it between trials; default 1.25)");
  if (!(o.limit > 0.0 && o.limit < 1.0))
    throw InputError("--limit", "", "must lie in (0, 1): the largest acceptable max overlap / d (Lan: 0.01)");
  if (o.start_k1 && !(*o.start_k1 > 0.0 && std::isfinite(*o.start_k1)))
    throw InputError("--start-k1", "", "must be a positive stiffness in N/m");
  if (o.duration && !(*o.duration > 0.0 && std::isfinite(*o.duration)))
    throw InputError("--duration", "", "must be a positive time in s");
  if (o.max_trials < 1) throw InputError("--max-trials", "", "must be at least 1");
}

// The case as far as calibrate needs it before choosing K1 (engine, model, the Hertz-equivalent
// K1). The law's stiffness (contact.k1) may be absent from the case: calibrate sets it, so a
// placeholder stands in here.
CaseConfig probe_case(const std::string& path, const std::vector<std::string>& overrides) {
  try {
    return load_case_unvalidated(path, overrides);
  } catch (const InputError& e) {
    std::string placeholder;
    dem::for_each_contact_law([&]<dem::ContactLaw Law>() {
      if (Law::calibrated_by_stiffness && e.key() == "contact." + std::string(Law::stiffness_key))
        placeholder = e.key() + "=1";
    });
    if (placeholder.empty()) throw;
    std::vector<std::string> with_stiffness = overrides;
    with_stiffness.push_back(placeholder);
    return load_case_unvalidated(path, with_stiffness);
  }
}

// The laws whose stiffness calibrate may choose, for its error message.
std::string calibrated_law_names() {
  std::string names;
  dem::for_each_contact_law([&]<dem::ContactLaw Law>() {
    if (Law::calibrated_by_stiffness) names += (names.empty() ? "" : ", ") + std::string(Law::name);
  });
  return names;
}

// Trial folders of an earlier calibration into the same folder (trial_ and digits).
void remove_old_trials(const fs::path& dir) {
  std::vector<fs::path> old;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && name.size() > 6 && name.rfind("trial_", 0) == 0 &&
        std::all_of(name.begin() + 6, name.end(), [](char ch) { return ch >= '0' && ch <= '9'; }))
      old.push_back(entry.path());
  }
  for (const auto& path : old) fs::remove_all(path);
}

double number_field(const io::FlatJsonFields& fields, const std::string& key, const std::string& file) {
  for (const auto& [name, value] : fields)
    if (name == key && value.kind == io::FlatJsonValue::Kind::number) return std::stod(value.text);
  throw RunError(file + ": no number '" + key + "'");
}

// One calibration: the probe case and the starting K1, then the trials, then the files. Each
// member function is one stage; the state they share is the members below.
class CalibrationRun {
 public:
  explicit CalibrationRun(const CalibrationOptions& options);
  int run();

 private:
  void choose_start(const SpeciesConfig& reference);
  CaseConfig trial_case(double k1) const;
  void warn_of_the_case();
  void print_header() const;
  double measure(double k1);
  void write_records(const StiffnessSearchResult& result, const TrialRecord* chosen, const TrialRecord* below,
                     const std::vector<std::string>& errors, double wall_seconds) const;
  void print_answer(const TrialRecord& chosen, const TrialRecord* below, double wall_seconds) const;

  const CalibrationOptions& o;
  CaseConfig probe;
  std::string stiffness_key;
  std::optional<double> hertz_k1;
  double expansion_time = 0.0;  // s, the trials' radius expansion
  double start_k1 = 0.0;
  std::string start_rule;
  double duration = 0.0;
  fs::path dir;
  std::vector<std::string> warnings;
  std::vector<TrialRecord> records;
};

}  // namespace

CalibrationRun::CalibrationRun(const CalibrationOptions& options) : o(options) {
  check_options(o);
  probe = probe_case(o.case_path, o.overrides);
  if (probe.engine.kind != "dem")
    throw InputError(o.case_path, "engine.kind",
                     "calibrate chooses the soft-sphere (dem) contact stiffness; event-driven hard spheres do not "
                     "overlap");
  const dem::DerivedQuantities probe_derived = dem::derive(probe);
  if (!probe_derived.calibrated_by_stiffness)
    throw InputError(o.case_path, "contact.model",
                     "calibrate chooses the loading stiffness of a law whose restitution does not change with it "
                     "(Lan 1994 section 4.1.3: " +
                         calibrated_law_names() + "); contact.model = \"" + probe.contact.model +
                         "\" is not supported");
  stiffness_key = "contact." + probe_derived.stiffness_key;
  hertz_k1 = probe_derived.hertz_k1;
  expansion_time = probe_derived.expansion_time;
  duration = o.duration.value_or(probe.run.duration);
  choose_start(probe.species[probe_derived.reference_species]);
  // The first trial's case now: an invalid case stops here, before anything is written.
  trial_case(trial_stiffness(start_k1, o.factor, 0));
  dir = o.output_directory.empty() ? fs::path("runs") / ("calibrate_" + fs::path(o.case_path).stem().string())
                                   : fs::path(o.output_directory);
}

// --start-k1, else Lan's rule: the Hertz-equivalent K1 / 100.
void CalibrationRun::choose_start(const SpeciesConfig& reference) {
  if (o.start_k1) {
    start_k1 = *o.start_k1;
    start_rule = "--start-k1";
  } else if (hertz_k1) {
    start_k1 = *hertz_k1 / 100.0;
    start_rule = "hertz_k1/100";
  } else if (reference.youngs_modulus > 0.0) {
    throw InputError(o.case_path, "drive",
                     "calibrate needs a starting K1: species '" + reference.name +
                         "' has a youngs_modulus, but the Hertz-equivalent K1 (eq. 2-5-10) needs an impact speed, "
                         "the peak speed of a [drive]; give --start-k1 K (N/m)");
  } else {
    throw InputError(o.case_path, "species.youngs_modulus",
                     "calibrate needs a starting K1: give --start-k1 K (N/m), or youngs_modulus (and poisson_ratio) "
                     "for species '" +
                         reference.name +
                         "' in a case with a [drive], so that Lan's start, the Hertz-equivalent K1 / 100, is known");
  }
}

CaseConfig CalibrationRun::trial_case(double k1) const {
  std::vector<std::string> overrides = o.overrides;
  overrides.push_back(stiffness_key + "=" + exact(k1));
  overrides.push_back("run.duration=" + exact(duration));
  overrides.push_back("run.halt_overlap=" + exact(o.limit));
  CaseConfig c = load_case(o.case_path, overrides);
  // A trial only measures the overlap: no snapshots or sampled files, and time-series rows (where
  // the overlap monitor looks) on a grid that ends exactly at the end of the trial.
  c.trajectory.enabled = false;
  c.observer_tables.erase(observe::ZoneSeriesObserver::table.table);
  c.output.snapshot_interval = 0.0;
  c.output.interval = c.run.duration / std::max(1.0, std::ceil(c.run.duration / c.output.interval - 1e-9));
  return c;
}

void CalibrationRun::warn_of_the_case() {
  if (probe.run.time_step > 0.0)
    warnings.push_back("run.time_step = " + fmt::format("{:.6g}", probe.run.time_step) +
                       " s is fixed by the case, so the time step does not follow K1 (eq. 2-5-4 would)");
  if (probe.drive.enabled && duration < probe.drive.start + probe.drive.ramp)
    warnings.push_back(
        fmt::format("the trials end at {:.6g} s, before the drive reaches its full amplitude at "
                    "drive.start + drive.ramp = {:.6g} s: the hardest impacts may be missed",
                    duration, probe.drive.start + probe.drive.ramp));
  if (probe.particles.init == "random" && duration <= expansion_time)
    warnings.push_back(
        fmt::format("the trials end within the radius expansion (particles.expansion_time = {:.6g} s), "
                    "which the overlap monitor ignores: every trial will pass",
                    expansion_time));
  for (const auto& w : warnings) std::cerr << "grainflow: warning: " << w << "\n";
}

void CalibrationRun::print_header() const {
  std::cout << fmt::format("calibrating K1 of {} (Lan 1994 section 4.1.3): max overlap <= {:.6g} d over {:.6g} s\n",
                           o.case_path, o.limit, duration);
  std::cout << fmt::format("start K1 = {:.6g} N/m ({}){}, factor {:.6g}, at most {} trials, trials in {}\n", start_k1,
                           start_rule == "--start-k1" ? "--start-k1" : "Hertz-equivalent K1 / 100",
                           hertz_k1 ? fmt::format(", Hertz-equivalent K1_H = {:.6g} N/m", *hertz_k1) : "", o.factor,
                           o.max_trials, dir.string());
  std::cout << fmt::format("{:>5}  {:>12}  {:>13}  {:>13}  {:>13}  {:>6}  {:>8}\n", "trial", "K1 [N/m]",
                           "time step [s]", "max overlap/d", "halted at [s]", "result", "wall [s]")
            << std::flush;
}

// One trial at `k1`, in-process; the overlap as the search compares it with the limit.
double CalibrationRun::measure(double k1) {
  const int width = std::max<int>(2, static_cast<int>(std::to_string(o.max_trials).size()));
  TrialRecord r;
  r.k1 = k1;
  r.folder = fmt::format("trial_{:0{}d}", records.size() + 1, width);
  CaseConfig c;
  try {
    c = trial_case(k1);
  } catch (const InputError& e) {
    throw RunError(fmt::format("trial {} (K1 = {:.6g} N/m): the case is not valid at this stiffness: {}",
                               records.size() + 1, k1, e.what()));
  }
  RunOptions run_options;
  run_options.output_directory = (dir / r.folder).string();
  run_options.threads = o.threads;
  run_options.quiet = o.quiet;
  run_options.echo_errors = false;
  const int status = run_dem(c, run_options);
  const std::string summary_path = (dir / r.folder / "summary.json").string();
  const io::FlatJsonFields summary = io::read_flat_json_file(summary_path);
  r.max_overlap = number_field(summary, "max_overlap_over_diameter", summary_path);
  r.time_step = number_field(summary, "time_step", summary_path);
  r.simulated_time = number_field(summary, "simulated_time", summary_path);
  r.wall_seconds = number_field(summary, "wall_seconds", summary_path);
  // A run fails (status 1) here only by the overlap halt: the overlap then exceeds the limit
  // (summary.json's 10 digits may round it onto the limit).
  r.halted = status != 0;
  if (r.halted && r.max_overlap < o.limit * (1.0 - 1e-8))
    throw RunError(
        fmt::format("trial {} (K1 = {:.6g} N/m) failed with the overlap within the limit: see the errors "
                    "in {}",
                    records.size() + 1, k1, summary_path));
  r.passed = !r.halted;
  std::cout << fmt::format("{:>5}  {:>12.6g}  {:>13.4g}  {:>13.4g}  {:>13}  {:>6}  {:>8.3g}\n", records.size() + 1,
                           r.k1, r.time_step, r.max_overlap,
                           r.halted ? fmt::format("{:.4g}", r.simulated_time) : std::string("-"),
                           r.passed ? "pass" : "fail", r.wall_seconds)
            << std::flush;
  records.push_back(r);
  if (records.size() == 1 && r.passed) {
    warnings.push_back(
        fmt::format("the start K1 = {:.6g} N/m already keeps the overlap within the limit (Lan starts "
                    "below and increases K1): stepping down by the factor to the smallest passing K1",
                    r.k1));
    std::cerr << "grainflow: warning: " << warnings.back() << "\n";
  }
  // The search compares with the limit: keep the verdict of the run's own monitor.
  return r.passed ? std::min(r.max_overlap, o.limit) : std::max(r.max_overlap, std::nextafter(o.limit, 1.0));
}

int CalibrationRun::run() {
  fs::create_directories(dir);
  remove_old_trials(dir);
  warn_of_the_case();
  print_header();
  const auto wall_start = std::chrono::steady_clock::now();
  const StiffnessSearchSettings settings{start_k1, o.factor, o.limit, o.max_trials};
  const StiffnessSearchResult result = search_stiffness(settings, [&](double k1) { return measure(k1); });
  const double wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();

  const TrialRecord* chosen = result.chosen ? &records[*result.chosen] : nullptr;
  // The failing neighbour that brackets the answer: K1 / factor.
  const TrialRecord* below = nullptr;
  if (chosen && result.bracketed)
    for (const auto& r : records)
      if (!r.passed && r.k1 < chosen->k1 && (!below || r.k1 > below->k1)) below = &r;
  if (result.descended && !result.bracketed) {
    warnings.push_back(
        fmt::format("no trial down to K1 = {:.6g} N/m exceeded the limit within --max-trials = {}: "
                    "the answer is not bracketed (raise --max-trials or --factor, or lower --start-k1)",
                    records.back().k1, o.max_trials));
    std::cerr << "grainflow: warning: " << warnings.back() << "\n";
  }
  std::vector<std::string> errors;
  if (!chosen)
    errors.push_back(
        fmt::format("no trial up to K1 = {:.6g} N/m kept the max overlap within {:.6g} d in --max-trials "
                    "= {} trials (raise --max-trials or --factor, or --start-k1)",
                    records.back().k1, o.limit, o.max_trials));
  write_records(result, chosen, below, errors, wall_seconds);
  if (!chosen) {
    std::cerr << "grainflow: calibration failed: " << errors.front() << "\n";
    return 1;
  }
  print_answer(*chosen, below, wall_seconds);
  return 0;
}

// calibration.csv (every trial) and calibration.json (the answer).
void CalibrationRun::write_records(const StiffnessSearchResult& result, const TrialRecord* chosen,
                                   const TrialRecord* below, const std::vector<std::string>& errors,
                                   double wall_seconds) const {
  io::write_atomically((dir / "calibration.csv").string(), [&](std::ostream& out) {
    out << "# grainflow calibrate " << o.case_path << ": limit " << exact(o.limit) << " d, factor " << exact(o.factor)
        << ", duration " << exact(duration) << " s\n";
    out << "# units: k1 N/m, time_step s, max_overlap_over_diameter 1, simulated_time s, wall_seconds s\n";
    out << "trial,k1,time_step,max_overlap_over_diameter,passed,halted,simulated_time,wall_seconds,chosen,folder\n";
    for (std::size_t i = 0; i < records.size(); ++i) {
      const auto& r = records[i];
      out << i + 1 << ',' << exact(r.k1) << ',' << exact(r.time_step) << ',' << exact(r.max_overlap) << ','
          << int(r.passed) << ',' << int(r.halted) << ',' << exact(r.simulated_time) << ',' << exact(r.wall_seconds)
          << ',' << int(chosen == &r) << ',' << r.folder << '\n';
    }
  });
  io::JsonObject json;
  json.string("case", o.case_path);
  json.string("version", kVersion);
  json.string("contact_model", probe.contact.model);
  json.boolean("converged", chosen != nullptr);
  json.boolean("bracketed", result.bracketed);
  json.boolean("descended", result.descended);
  json.number("k1", chosen ? chosen->k1 : kNone);
  json.number("time_step", chosen ? chosen->time_step : kNone);
  json.number("max_overlap_over_diameter", chosen ? chosen->max_overlap : kNone);
  json.number("failing_k1", below ? below->k1 : kNone);
  json.number("failing_max_overlap_over_diameter", below ? below->max_overlap : kNone);
  json.number("hertz_k1", hertz_k1.value_or(kNone));
  json.number("k1_over_hertz_k1", chosen && hertz_k1 ? chosen->k1 / *hertz_k1 : kNone);
  json.integer("trials", static_cast<long long>(records.size()));
  json.number("start_k1", start_k1);
  json.string("start_rule", start_rule);
  json.number("factor", o.factor);
  json.number("overlap_limit", o.limit);
  json.number("duration", duration);
  json.integer("max_trials", o.max_trials);
  json.boolean("time_step_from_case", probe.run.time_step > 0.0);
  json.number("wall_seconds", wall_seconds);
  json.strings("errors", errors);
  json.strings("warnings", warnings);
  io::write_atomically((dir / "calibration.json").string(), [&](std::ostream& out) { json.write(out); });
}

void CalibrationRun::print_answer(const TrialRecord& chosen, const TrialRecord* below, double wall_seconds) const {
  std::cout << fmt::format("\nK1 = {:.6g} N/m: max overlap {:.4g} d <= {:.6g} d", chosen.k1, chosen.max_overlap,
                           o.limit);
  if (below) std::cout << fmt::format("; K1 = {:.6g} N/m exceeded it ({:.4g} d)", below->k1, below->max_overlap);
  std::cout << fmt::format("\ntime step {:.6g} s{}\n", chosen.time_step,
                           probe.run.time_step > 0.0 ? " (run.time_step of the case)" : " (eq. 2-5-4)");
  if (hertz_k1)
    std::cout << fmt::format("Hertz-equivalent K1_H = {:.6g} N/m: K1 / K1_H = {:.3g}\n", *hertz_k1,
                             chosen.k1 / *hertz_k1);
  std::cout << fmt::format("{} trials, {:.3g} s; wrote {} and {}\n", records.size(), wall_seconds,
                           (dir / "calibration.csv").string(), (dir / "calibration.json").string());
  std::cout << "paste into the case's [contact] table:\n" << fmt::format("k1 = {:.6g}\n", chosen.k1);
}

int run_calibration(const CalibrationOptions& options) { return CalibrationRun(options).run(); }

}  // namespace grainflow::run
