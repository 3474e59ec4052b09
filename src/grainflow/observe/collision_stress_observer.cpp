#include "grainflow/observe/collision_stress_observer.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "grainflow/analysis/savage_jeffrey.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/analysis/least_squares_line.hpp"
#include "grainflow/observe/stress_files.hpp"

namespace grainflow::observe {
CollisionStressObserver::CollisionStressObserver(const RunContext& run, const Frame& start)
    : c_(*run.c),
      frame_(&start),
      dim_(start.dimension),
      strips_(*run.c, start),
      stress_(strips_.count(), start.box->periodic[StripLayout::kAxis] ? start.box->length(StripLayout::kAxis) : 0.0),
      walls_(start.walls),
      interval_(run.c->output.profile_interval > 0.0 ? run.c->output.profile_interval : run.c->output.interval / 10.0),
      next_(first_grid_index(start.time, interval_)) {}

double CollisionStressObserver::wall_area(int wall) const {
  return observe::wall_area(*frame_->box, frame_->walls[static_cast<std::size_t>(wall)].axis, dim_);
}

void CollisionStressObserver::on_pair(const engine_api::PairCollision& c) {
  stress_.add(strips_.grid_at(*frame_, c.time), c);
  angles_.add(c.normal);
}

void CollisionStressObserver::on_wall(const engine_api::WallCollision& c) {
  stress_.add(strips_.grid_at(*frame_, c.time), c);
  walls_.add(c, wall_area(c.wall));
}

void CollisionStressObserver::sample(const Frame& now) {
  ++next_;
  frame_ = &now;
  const double t = now.time;
  if (!started_) {
    if (!(t > c_.output.average_start && now.collisions >= c_.output.average_start_collisions)) return;
    stress_.begin(strips_.grid_at(now, t), *now.particles, t);
    started_ = true;
    last_ = t;
    return;
  }
  close_interval(now);
}

void CollisionStressObserver::close_interval(const Frame& now) {
  const double t = now.time;
  if (!(t > last_)) return;
  const StripGrid grid = strips_.grid_at(now, t);
  const double duration = t - last_;
  const ParticleStore& p = *now.particles;
  if (now.wall_contacts)
    now.wall_contacts([&](std::uint32_t i, int w, const Vec3& force) {
      Vec3 contact = p.position[i];
      const FaceWall& wall = now.walls[static_cast<std::size_t>(w)];
      contact[wall.axis] = wall.at(t);
      walls_.add_rolling(w, force, duration, wall_area(w));
      stress_.add_contact_force(grid, p.position[i], contact, force, duration);
    });
  stress_.sample(grid, p, t);
  walls_.close_interval(duration);
  last_ = t;
}

// Savage and Jeffrey's S = 2R (du/dy) / sqrt(<v'^2>) for the whole cell: du/dy from a mass-weighted
// least-squares line through the strips' mean u_x, <v'^2> the mass-weighted mean of P_yy(kinetic)/rho.
// A single number suits a Couette cell's linear profile; for a chute it is only a rough average.
double CollisionStressObserver::shear_parameter(const std::vector<StripStress>& strips) const {
  std::vector<double> y, u, mass;
  double kinetic = 0.0;
  for (const auto& s : strips) {
    if (!(s.mass_density > 0.0)) continue;
    y.push_back(0.5 * (s.lo + s.hi));
    u.push_back(s.mean_velocity.x);
    mass.push_back(s.mass_density);
    kinetic += s.kinetic[4];  // yy
  }
  const analysis::LeastSquaresLine line = analysis::fit_least_squares_line(y, u, mass);
  if (!(line.sxx > 0.0)) return 0.0;
  const double w = line.weight, shear_rate = line.slope;
  double radius = 0.0;
  for (double r : frame_->particles->radius) radius += r;
  radius /= std::max<std::size_t>(1, frame_->particles->size());
  return analysis::savage_jeffrey_shear_parameter(radius, shear_rate, kinetic / w);
}

std::vector<StripStress> CollisionStressObserver::strip_stresses() const {
  return stress_.averages(c_.gravity, top_wall_row(walls_.averages(), frame_->walls, strips_.between_walls()));
}

void CollisionStressObserver::write(const Frame& last, OutputSink& out) {
  if (started_) close_interval(last);
  const std::string& dir = out.directory;
  io::JsonObject& summary = *out.summary;
  std::vector<std::string>& warnings = *out.warnings;
  if (!started_ || stress_.samples() == 0)
    warnings.push_back(
        "stresses.csv, walls.csv, collision_angles.csv: no averaging interval completed after "
        "output.average_start (and output.average_start_collisions); their values are nan");
  const std::vector<WallLoad> loads = walls_.averages();
  const auto strips = strip_stresses();
  const double s = shear_parameter(strips);
  write_stresses(dir + "/stresses.csv", strips);
  write_walls(dir + "/walls.csv", loads);
  write_angles(dir + "/collision_angles.csv", s);

  add_stress_summary(summary, stress_, loads, frame_->walls);
  summary.number("savage_jeffrey_S", s);
}

void CollisionStressObserver::write_stresses(const std::string& path, const std::vector<StripStress>& strips) const {
  write_stress_file(path, strips, StressFileLayout{dim_, strips_.between_walls(), "collisional", true});
}

void CollisionStressObserver::write_walls(const std::string& path, const std::vector<WallLoad>& loads) const {
  std::vector<double> areas;
  for (std::size_t w = 0; w < loads.size(); ++w) areas.push_back(wall_area(static_cast<int>(w)));
  write_wall_file(path, loads, frame_->walls, areas, frame_->time, dim_);
}

void CollisionStressObserver::write_angles(const std::string& path, double shear_parameter) const {
  io::write_atomically(path, [&](std::ostream& out) {
    out << "# units: theta_deg degrees (bin centre; line of centres from the flow direction x towards y, folded "
           "into [0, 180)), density 1/rad, count collisions, savage_jeffrey 1/rad at S = "
        << shear_parameter << "\n";
    out << "theta_deg,density,count,savage_jeffrey\n";
    for (int k = 0; k < angles_.bins(); ++k) {
      const double theta = angles_.centre(k);
      out << theta * 180.0 / M_PI << ',' << angles_.density(k) << ',' << angles_.count(k) << ','
          << analysis::savage_jeffrey_angle_density(theta, shear_parameter) << '\n';
    }
  });
}

}  // namespace grainflow::observe
