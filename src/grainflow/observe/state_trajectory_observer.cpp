#include "grainflow/observe/state_trajectory_observer.hpp"

#include <algorithm>
#include <limits>

#include "grainflow/core/version.hpp"

namespace grainflow::observe {

StateTrajectoryObserver::StateTrajectoryObserver(const RunContext& run, const Frame& s)
    : file_(run.directory + "/trajectory.h5"),
      strips_(*run.c, s),
      start_(trajectory_start(*run.c)),
      interval_(edmd_trajectory_interval(*run.c)),
      requested_(run.c->trajectory.samples) {
  const CaseConfig& c = *run.c;
  const ParticleStore& p = *s.particles;
  std::vector<std::uint32_t> ids = c.trajectory.particles;
  if (ids.empty())
    for (std::size_t i = 0; i < p.size(); ++i) ids.push_back(p.id[i]);
  std::sort(ids.begin(), ids.end());
  followed_ = ids.size();
  std::uint32_t largest = 0;
  for (auto id : p.id) largest = std::max(largest, id);
  column_of_id_.assign(p.size() == 0 ? 0 : largest + 1, -1);
  for (std::size_t k = 0; k < ids.size(); ++k) column_of_id_[ids[k]] = static_cast<std::int32_t>(k);
  wall_lo_ = s.walls.with_role(WallRole::shear_bottom);
  wall_hi_ = s.walls.with_role(WallRole::shear_top);

  // Per followed particle: id and radius; the rotational inertia factor I / (m R^2) is one number.
  std::vector<double> radius(followed_, 0.0);
  double inertia_factor = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int k = column_of_id_[p.id[i]];
    if (k < 0) continue;
    radius[k] = p.radius[i];
    inertia_factor = 1.0 / (p.inv_inertia[i] * p.mass[i] * p.radius[i] * p.radius[i]);
  }
  file_.write("/id", std::vector<std::int64_t>(ids.begin(), ids.end()));
  file_.write("/radius", radius, {followed_});
  file_.attribute("/", "engine", std::string("edmd"));
  file_.attribute("/", "dimension", static_cast<std::int64_t>(s.dimension));
  file_.attribute("/", "flow_axis", std::int64_t{0});
  file_.attribute("/", "gradient_axis", std::int64_t{StripLayout::kAxis});
  file_.attribute("/", "inertia_factor", inertia_factor);
  file_.attribute("/", "particles_total", static_cast<std::int64_t>(p.size()));
  file_.attribute("/", "strip_count", static_cast<std::int64_t>(strips_.count()));
  file_.attribute("/", "period_y", s.box->periodic[1] ? s.box->length(1) : 0.0);
  if (s.dimension == 3) {
    file_.attribute("/", "box_depth", s.box->length(2));
    file_.attribute("/", "z_lo", s.box->lo[2]);
    file_.attribute("/", "periodic_z", static_cast<std::int64_t>(s.box->periodic[2] ? 1 : 0));
  }
  file_.attribute("/", "start", start_);
  file_.attribute("/", "interval", interval_);
  file_.attribute("/", "samples_requested", static_cast<std::int64_t>(requested_));
  file_.attribute("/", "case", c.path);
  file_.attribute("/", "version", std::string(kVersion));
  file_.attribute(
      "/", "units",
      std::string("time s, position m (unwrapped), velocity m/s, angular_velocity rad/s, radius m, wall_lo, "
                  "wall_hi, strip_lo, strip_hi, box_width m"));
  const auto n = static_cast<unsigned long long>(followed_);
  time_ = file_.growing("/time", {}, 1024);
  position_ = file_.growing("/position", {n, 3}, 16);
  velocity_ = file_.growing("/velocity", {n, 3}, 16);
  angular_velocity_ = file_.growing("/angular_velocity", {n, 3}, 16);
  wall_lo_at_ = file_.growing("/wall_lo", {}, 1024);
  wall_hi_at_ = file_.growing("/wall_hi", {}, 1024);
  strip_lo_ = file_.growing("/strip_lo", {}, 1024);
  strip_hi_ = file_.growing("/strip_hi", {}, 1024);
  width_ = file_.growing("/box_width", {}, 1024);
  row_x_.assign(3 * followed_, 0.0);
  row_v_.assign(3 * followed_, 0.0);
  row_w_.assign(3 * followed_, 0.0);
}

double StateTrajectoryObserver::next_time() const {
  if (taken_ >= requested_) return std::numeric_limits<double>::infinity();
  return start_ + static_cast<double>(taken_) * interval_;
}

void StateTrajectoryObserver::sample(const Frame& s) {
  const ParticleStore& p = *s.particles;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int k = column_of_id_[p.id[i]];
    if (k < 0) continue;
    const Vec3 x = s.box->unwrapped(p.position[i], p.image[i]);
    for (int a = 0; a < 3; ++a) {
      row_x_[3 * k + a] = x[a];
      row_v_[3 * k + a] = p.velocity[i][a];
      row_w_[3 * k + a] = p.angular_velocity[i][a];
    }
  }
  const double t = s.time;
  const double lo = wall_lo_ >= 0 ? s.walls[wall_lo_].at(t) : s.box->lo[1];
  const double hi = wall_hi_ >= 0 ? s.walls[wall_hi_].at(t) : s.box->hi[1];
  const StripGrid grid = strips_.grid_at(s, t);
  const double strip_lo = grid.lo(), strip_hi = grid.hi(), width = s.box->length(0);
  time_.append(&t);
  position_.append(row_x_.data());
  velocity_.append(row_v_.data());
  angular_velocity_.append(row_w_.data());
  wall_lo_at_.append(&lo);
  wall_hi_at_.append(&hi);
  strip_lo_.append(&strip_lo);
  strip_hi_.append(&strip_hi);
  width_.append(&width);
  ++taken_;
}

void StateTrajectoryObserver::finish(OutputSink& out) {
  file_.attribute("/", "samples", static_cast<std::int64_t>(taken_));
  if (taken_ < requested_)
    out.warnings->push_back("trajectory: the run ended after " + std::to_string(taken_) + " of the " +
                            std::to_string(requested_) +
                            " requested samples (trajectory.start, interval and samples need a longer run.duration)");
  file_.commit();
}

}  // namespace grainflow::observe
