#include "grainflow/observe/zone_series_observer.hpp"

#include "grainflow/config/case_checks.hpp"
#include "grainflow/config/sampler_tables.hpp"
#include "grainflow/config/toml_reader.hpp"
#include "grainflow/observe/floor_motion.hpp"
#include "grainflow/observe/sample_file.hpp"
#include "grainflow/observe/zone_profile_observer.hpp"

namespace grainflow::observe {
namespace {

constexpr long long kDefaultSamples = 2048;
constexpr long long kFewestSamples = 16;  // a spectrum of fewer says nothing

void read_table(TomlReader& r, const CaseConfig&, ObserverParameters& out) {
  double start = -1.0;
  long long samples = kDefaultSamples;
  read_sampling(r, start, samples, kFewestSamples);
  if (r.has("start")) out.set_number("start", start);
  out.set_integer("samples", samples);
  const double interval = r.number("interval", 0.0);
  if (interval < 0.0) r.fail("interval", "must not be negative (0 = 20 samples per drive period)");
  out.set_number("interval", interval);
}

// The drive's frequency along gravity (0 without a drive): the default interval is 1 / (20 f).
double drive_frequency(const CaseConfig& c, int gravity_axis) {
  return c.drive.enabled ? c.drive.frequency[gravity_axis] : 0.0;
}

void check_table(const ObserverParameters& table, const ObserverCheckInputs& run) {
  const double f = drive_frequency(run.c, run.gravity_axis);
  const double given = table.number("interval");
  if (given == 0.0 && !(f > 0.0))
    case_checks::fail(run.c, "zone_series.interval",
                      "needs a value: there is no drive along gravity to take 20 samples per period of");
  const double interval = given > 0.0 ? given : 1.0 / (20.0 * f);
  if (interval < run.time_step) case_checks::fail(run.c, "zone_series.interval", "is shorter than one time step");
}

}  // namespace

const ObserverSchema ZoneSeriesObserver::table = {
    "zone_series", "dem", "zone velocity histories are implemented for the DEM engine only", &read_table, &check_table};

ZoneSeriesObserver::ZoneSeriesObserver(const RunContext& run) : c_(*run.c), zones_(ZoneLayout(run).profile(run)) {
  const CaseConfig& c = c_;
  const ObserverParameters& t = c.observer_tables.at(table.table);
  requested_ = t.integer("samples");
  const double f = drive_frequency(c, run.gravity_axis);
  interval_ = t.number("interval") > 0.0 ? t.number("interval") : 1.0 / (20.0 * f);
  start_ = t.has("start") ? t.number("start") : c.output.average_start;
  if (!run.writes) return;
  file_.emplace(run.directory + "/zone_series.h5");
  const auto centres = zones_.zone_centres();
  file_->write("/zone_centre", centres, {centres.size()});
  write_run_attributes(*file_, run, start_,
                       "time s, zone_velocity m/s, floor_position m, floor_velocity m/s, zone_centre m");
  file_->attribute("/", "interval", interval_);
  file_->attribute("/", "drive_frequency", f);
  time_ = file_->growing("/time", {}, 1024);
  zone_velocity_ = file_->growing("/zone_velocity", {centres.size(), 3}, 64);
  floor_position_ = file_->growing("/floor_position", {}, 1024);
  floor_velocity_ = file_->growing("/floor_velocity", {}, 1024);
}

void ZoneSeriesObserver::sample(const Frame& now) {
  if (taken_ >= requested_ || now.time < start_ + next_ * interval_ - 0.5 * now.time_step) return;
  ++next_;
  const FloorMotion floor = floor_motion(now.walls, c_);
  const auto u = zones_.instantaneous_mean_velocity(*now.particles);  // over every rank
  ++taken_;
  if (!file_) return;
  std::vector<double> row;
  row.reserve(3 * u.size());
  for (const Vec3& v : u) row.insert(row.end(), {v.x, v.y, v.z});
  time_.append(&now.time);
  zone_velocity_.append(row.data());
  floor_position_.append(&floor.position);
  floor_velocity_.append(&floor.velocity);
}

void ZoneSeriesObserver::finish(OutputSink& out) {
  if (file_) finish_samples(*file_, "zone_series", taken_, requested_, *out.warnings);
}

}  // namespace grainflow::observe
