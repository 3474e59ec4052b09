#include "grainflow/observe/zone_series_observer.hpp"

#include "grainflow/observe/floor_motion.hpp"
#include "grainflow/observe/sample_file.hpp"
#include "grainflow/observe/zone_profile_observer.hpp"

namespace grainflow::observe {

ZoneSeriesObserver::ZoneSeriesObserver(const RunContext& run)
    : c_(*run.c), zones_(ZoneLayout(run).profile(run)), requested_(run.c->zone_series.samples) {
  const CaseConfig& c = c_;
  const double f = c.drive.enabled ? c.drive.frequency[run.gravity_axis] : 0.0;
  interval_ = c.zone_series.interval > 0.0 ? c.zone_series.interval : 1.0 / (20.0 * f);
  start_ = c.zone_series.start >= 0.0 ? c.zone_series.start : c.output.average_start;
  if (!run.writes) return;
  file_.emplace(run.directory + "/zone_series.h5");
  const auto centres = zones_.zone_centres();
  file_->write("/zone_centre", centres, {centres.size()});
  write_run_attributes(*file_, run, start_, "time s, zone_velocity m/s, floor_position m, floor_velocity m/s, zone_centre m");
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
