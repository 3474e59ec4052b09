#include "grainflow/observe/contact_stress_observer.hpp"

#include "grainflow/observe/stress_files.hpp"

namespace grainflow::observe {

ContactStressObserver::ContactStressObserver(const RunContext& run, const Frame& start)
    : c_(*run.c),
      ranks_(run.ranks),
      frame_(&start),
      strips_(*run.c, start),
      stress_(strips_.count(), start.box->periodic[StripLayout::kAxis] ? start.box->length(StripLayout::kAxis) : 0.0),
      walls_(start.walls),
      schedule_(run.c->output.profile_interval > 0.0 ? run.c->output.profile_interval : run.c->output.interval / 10.0,
                run.time_step) {}

void ContactStressObserver::sample(const Frame& now) {
  if (!schedule_.due(now.step)) return;
  frame_ = &now;
  const double t = now.time;
  const StripGrid grid = strips_.grid_at(now, t);
  const ParticleStore& p = *now.particles;
  if (!started_) {
    if (!(t >= c_.output.average_start)) return;
    stress_.begin(grid, p, t, ranks_);
    started_ = true;
    last_ = t;
    return;
  }
  const double duration = t - last_;
  if (!(duration > 0.0)) return;
  // The forces now stand for the interval just ended (a rectangle rule in time, as the kinetic part).
  now.contact_forces([&](std::uint32_t i, int wall, const Vec3& from, const Vec3& force) {
    stress_.add_contact_force(grid, p.position[i], from, force, duration);
    if (wall >= 0 && static_cast<std::size_t>(wall) < now.walls.size()) {  // a box face (walls.csv's rows)
      const int axis = now.walls[static_cast<std::size_t>(wall)].axis;
      walls_.add_rolling(wall, force, duration, wall_area(*now.box, axis, now.dimension));
    }
  });
  stress_.sample(grid, p, t, ranks_);
  walls_.close_interval(duration, ranks_);
  last_ = t;
}

std::vector<StripStress> ContactStressObserver::strip_stresses() const {
  return stress_.averages(c_.gravity, top_wall_row(walls_.averages(), frame_->walls, strips_.between_walls()));
}

void ContactStressObserver::write(const Frame& last, OutputSink& out) {
  frame_ = &last;
  if (!started_ || stress_.samples() == 0)
    out.warnings->push_back("stresses.csv, walls.csv: no sample after output.average_start; their values are nan");
  const std::vector<WallLoad> loads = walls_.averages();
  const int dim = last.dimension;
  if (out.writes) {
    write_stress_file(out.directory + "/stresses.csv", strip_stresses(),
                      StressFileLayout{dim, strips_.between_walls(), "contact", false});
    std::vector<double> areas;
    for (const auto& w : last.walls) areas.push_back(wall_area(*last.box, w.axis, dim));
    write_wall_file(out.directory + "/walls.csv", loads, last.walls, areas, last.time, dim);
  }
  add_stress_summary(*out.summary, stress_, loads, last.walls);
}

}  // namespace grainflow::observe
