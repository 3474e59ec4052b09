#include "grainflow/observe/collision_stress_observer.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "grainflow/analysis/savage_jeffrey.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/analysis/least_squares_line.hpp"

namespace grainflow::observe {
namespace {

constexpr const char* kAxisNames = "xyz";

std::string component_name(int a, int b) { return std::string{kAxisNames[a], kAxisNames[b]}; }

}  // namespace

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
  const int axis = frame_->walls[static_cast<std::size_t>(wall)].axis;
  double area = 1.0;
  for (int a = 0; a < dim_; ++a)
    if (a != axis) area *= frame_->box->length(a);
  return area;
}

void CollisionStressObserver::on_pair(const PairCollision& c) {
  stress_.add(strips_.grid_at(*frame_, c.time), c);
  angles_.add(c.normal);
}

void CollisionStressObserver::on_wall(const WallCollision& c) {
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
  const std::vector<WallLoad> loads = walls_.averages();
  Vec3 top_row;  // P_y. at the top of the strips: the top wall's, or zero at a free surface
  for (std::size_t w = 0; w < loads.size(); ++w)
    if (strips_.between_walls() && frame_->walls[w].face == 3) top_row = loads[w].row;
  return stress_.averages(c_.gravity, top_row);
}

void CollisionStressObserver::write(const Frame& last, OutputSink& out) {
  if (started_) close_interval(last);
  const std::string& dir = out.directory;
  io::JsonObject& summary = *out.summary;
  std::vector<std::string>& warnings = *out.warnings;
  if (!started_ || stress_.samples() == 0)
    warnings.push_back("stresses.csv, walls.csv, collision_angles.csv: no averaging interval completed after "
                       "output.average_start (and output.average_start_collisions); their values are nan");
  const std::vector<WallLoad> loads = walls_.averages();
  const auto strips = strip_stresses();
  const double s = shear_parameter(strips);
  write_stresses(dir + "/stresses.csv", strips);
  write_walls(dir + "/walls.csv", loads);
  write_angles(dir + "/collision_angles.csv", s);

  summary.integer("stress_samples", stress_.samples());
  summary.number("stress_averaging_time", stress_.elapsed());
  for (std::size_t w = 0; w < loads.size(); ++w) {
    const std::string face = kFaceNames[frame_->walls[w].face];
    summary.number("wall_normal_stress_" + face, loads[w].normal_stress);
    summary.number("wall_normal_stress_error_" + face, loads[w].normal_stress_error);
    summary.number("wall_shear_stress_" + face, loads[w].shear_stress);
    summary.number("wall_shear_stress_error_" + face, loads[w].shear_stress_error);
    summary.number("wall_friction_" + face, loads[w].friction);
  }
  summary.number("savage_jeffrey_S", s);
}

void CollisionStressObserver::write_stresses(const std::string& path, const std::vector<StripStress>& strips) const {
  const bool walls = strips_.between_walls();
  const char* stress = dim_ == 2 ? "N/m" : "Pa";
  const char* measure = dim_ == 2 ? "m^2" : "m^3";
  io::write_atomically(path, [&](std::ostream& out) {
    out << "# units: y m (strip centre), stresses " << stress
        << " (P_ab: flux of b-momentum across a plane normal to a; compressive positive), *_error: standard errors by "
           "block averaging (nan: too few samples), number: mean particle centres, mass_density kg/"
        << measure << ", collision_rate 1/(s " << measure << "), collision_rate_per_particle 1/s, dissipation_rate W/"
        << measure << ", momentum_rate N/" << measure << ", weight_* " << stress << "\n";
    out << "y";
    if (walls) out << ",y_over_H";
    for (const char* part : {"collisional", "kinetic", "total"})
      for (int a = 0; a < dim_; ++a)
        for (int b = 0; b < dim_; ++b) out << ',' << part << '_' << component_name(a, b) << ',' << part << '_' << component_name(a, b) << "_error";
    out << ",number,mass_density,collision_rate,collision_rate_per_particle,dissipation_rate";
    for (int b = 0; b < dim_; ++b) out << ",momentum_rate_" << kAxisNames[b];
    for (int b = 0; b < dim_; ++b) out << ",weight_y" << kAxisNames[b];
    out << '\n';
    const double lo = strips.empty() ? 0.0 : strips.front().lo, hi = strips.empty() ? 0.0 : strips.back().hi;
    for (const auto& s : strips) {
      const double y = 0.5 * (s.lo + s.hi);
      out << y;
      if (walls) out << ',' << (y - lo) / (hi - lo);
      for (auto [value, error] : {std::pair{&s.collisional, &s.collisional_error}, std::pair{&s.kinetic, &s.kinetic_error},
                                  std::pair{&s.total, &s.total_error}})
        for (int a = 0; a < dim_; ++a)
          for (int b = 0; b < dim_; ++b) out << ',' << (*value)[a * 3 + b] << ',' << (*error)[a * 3 + b];
      out << ',' << s.number << ',' << s.mass_density << ',' << s.collision_rate << ',' << s.collision_rate_per_particle
          << ',' << s.dissipation_rate;
      for (int b = 0; b < dim_; ++b) out << ',' << s.momentum_rate[b];
      for (int b = 0; b < dim_; ++b) out << ',' << s.weight_row[b];
      out << '\n';
    }
  });
}

void CollisionStressObserver::write_walls(const std::string& path, const std::vector<WallLoad>& loads) const {
  const char* stress = dim_ == 2 ? "N/m" : "Pa";
  const char* area = dim_ == 2 ? "m" : "m^2";
  io::write_atomically(path, [&](std::ostream& out) {
    out << "# units: position m, area " << area << ", stresses " << stress
        << " (the wall's row of P_ab: normal compressive positive, shear along the flow), impulse_angle_deg degrees, "
           "collision_rate 1/(s "
        << area << "), dissipation_rate W/" << area << "\n";
    out << "wall,axis,position,area,collisions,normal_stress,normal_stress_error,shear_stress,shear_stress_error,"
           "friction,impulse_angle_deg,rolling_normal_stress,rolling_shear_stress,collision_rate,dissipation_rate\n";
    for (std::size_t w = 0; w < loads.size(); ++w) {
      const auto& wall = frame_->walls[w];
      const auto& l = loads[w];
      out << kFaceNames[wall.face] << ',' << kAxisNames[wall.axis] << ',' << wall.at(frame_->time) << ','
          << wall_area(static_cast<int>(w)) << ',' << l.collisions << ',' << l.normal_stress << ',' << l.normal_stress_error
          << ',' << l.shear_stress << ',' << l.shear_stress_error << ',' << l.friction << ',' << l.impulse_angle_deg << ','
          << l.rolling_normal_stress << ',' << l.rolling_shear_stress << ',' << l.collision_rate << ','
          << l.dissipation_rate << '\n';
    }
  });
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
