#include "grainflow/observe/window_trajectory_observer.hpp"

#include <algorithm>

#include "grainflow/observe/sample_file.hpp"

namespace grainflow::observe {

WindowTrajectoryObserver::WindowTrajectoryObserver(const RunContext& run, const ParticleStore& everyone)
    : requested_(run.c->trajectory.samples) {
  const CaseConfig& c = *run.c;
  const auto& t = c.trajectory;
  std::vector<std::uint32_t> ids = t.particles;
  if (ids.empty())
    for (std::size_t i = 0; i < everyone.size(); ++i)
      if (everyone.motion[i] == Motion::free) ids.push_back(everyone.id[i]);
  std::sort(ids.begin(), ids.end());
  const double window = t.window > 0.0 ? t.window : 0.5 * c.run.collision_steps * run.time_step;
  const double start = t.start >= 0.0 ? t.start : c.output.average_start;
  if (run.writes) {
    file_.emplace(run.directory + "/trajectory.h5");
    std::vector<std::int64_t> id_column(ids.begin(), ids.end());
    file_->write("/id", id_column);
    write_run_attributes(*file_, run, start, "time s, velocity m/s, position m (unwrapped), window and time_step s");
    file_->attribute("/", "window", window);
    file_->attribute("/", "samples_requested", static_cast<std::int64_t>(t.samples));
    file_->attribute("/", "max_lag", static_cast<std::int64_t>(t.max_lag > 0 ? t.max_lag : t.samples / 2));
    file_->attribute("/", "restitution", run.restitution);  // the binary contact's, for Savage–Dai's D
    const auto n = static_cast<unsigned long long>(ids.size());
    time_ = file_->growing("/time", {}, 1024);
    velocity_ = file_->growing("/velocity", {n, 3}, 16);
    position_ = file_->growing("/position", {n, 3}, 16);
  }
  sampler_.emplace(std::move(ids), start, window, t.samples,
                   [this](double when, const std::vector<double>& v, const std::vector<double>& x) {
                     if (!file_) return;
                     time_.append(&when);
                     velocity_.append(v.data());
                     position_.append(x.data());
                   });
  sampler_->set_reduce(run.ranks);
}

void WindowTrajectoryObserver::finish(OutputSink& out) {
  if (file_) finish_samples(*file_, "trajectory", sampler_->taken(), requested_, *out.warnings);
}

}  // namespace grainflow::observe
