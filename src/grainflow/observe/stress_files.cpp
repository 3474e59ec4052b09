#include "grainflow/observe/stress_files.hpp"

#include <limits>
#include <ostream>
#include <utility>

#include "grainflow/config/case_config.hpp"
#include "grainflow/io/atomic_file.hpp"

namespace grainflow::observe {
namespace {

constexpr const char* kAxisNames = "xyz";

std::string component_name(int a, int b) { return std::string{kAxisNames[a], kAxisNames[b]}; }

}  // namespace

void write_stress_file(const std::string& path, const std::vector<StripStress>& strips,
                       const StressFileLayout& layout) {
  const int dim_ = layout.dimension;
  const bool walls = layout.between_walls;
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
    for (const char* part : {layout.contact_part, "kinetic", "total"})
      for (int a = 0; a < dim_; ++a)
        for (int b = 0; b < dim_; ++b)
          out << ',' << part << '_' << component_name(a, b) << ',' << part << '_' << component_name(a, b) << "_error";
    out << ",number,mass_density,collision_rate,collision_rate_per_particle,dissipation_rate";
    for (int b = 0; b < dim_; ++b) out << ",momentum_rate_" << kAxisNames[b];
    for (int b = 0; b < dim_; ++b) out << ",weight_y" << kAxisNames[b];
    out << '\n';
    const double lo = strips.empty() ? 0.0 : strips.front().lo, hi = strips.empty() ? 0.0 : strips.back().hi;
    for (const auto& s : strips) {
      const double y = 0.5 * (s.lo + s.hi);
      out << y;
      if (walls) out << ',' << (y - lo) / (hi - lo);
      for (auto [value, error] : {std::pair{&s.collisional, &s.collisional_error},
                                  std::pair{&s.kinetic, &s.kinetic_error}, std::pair{&s.total, &s.total_error}})
        for (int a = 0; a < dim_; ++a)
          for (int b = 0; b < dim_; ++b) out << ',' << (*value)[a * 3 + b] << ',' << (*error)[a * 3 + b];
      const double nan = std::numeric_limits<double>::quiet_NaN();
      out << ',' << s.number << ',' << s.mass_density << ',' << (layout.collisions ? s.collision_rate : nan) << ','
          << (layout.collisions ? s.collision_rate_per_particle : nan) << ','
          << (layout.collisions ? s.dissipation_rate : nan);
      for (int b = 0; b < dim_; ++b) out << ',' << s.momentum_rate[b];
      for (int b = 0; b < dim_; ++b) out << ',' << s.weight_row[b];
      out << '\n';
    }
  });
}

void write_wall_file(const std::string& path, const std::vector<WallLoad>& loads, const FaceWalls& frame_walls,
                     const std::vector<double>& areas, double time, int dim_) {
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
      const auto& wall = frame_walls[w];
      const auto& l = loads[w];
      out << kFaceNames[wall.face] << ',' << kAxisNames[wall.axis] << ',' << wall.at(time) << ',' << areas[w] << ','
          << l.collisions << ',' << l.normal_stress << ',' << l.normal_stress_error << ',' << l.shear_stress << ','
          << l.shear_stress_error << ',' << l.friction << ',' << l.impulse_angle_deg << ',' << l.rolling_normal_stress
          << ',' << l.rolling_shear_stress << ',' << l.collision_rate << ',' << l.dissipation_rate << '\n';
    }
  });
}

Vec3 top_wall_row(const std::vector<WallLoad>& loads, const FaceWalls& walls, bool between_walls) {
  for (std::size_t w = 0; w < loads.size(); ++w)
    if (between_walls && walls[w].plays(WallRole::shear_top)) return loads[w].row;
  return {};
}

void add_stress_summary(io::JsonObject& summary, const StressProfile& stress, const std::vector<WallLoad>& loads,
                        const FaceWalls& walls) {
  summary.integer("stress_samples", stress.samples());
  summary.number("stress_averaging_time", stress.elapsed());
  for (std::size_t w = 0; w < loads.size(); ++w) {
    const std::string face = kFaceNames[walls[w].face];
    summary.number("wall_normal_stress_" + face, loads[w].normal_stress);
    summary.number("wall_normal_stress_error_" + face, loads[w].normal_stress_error);
    summary.number("wall_shear_stress_" + face, loads[w].shear_stress);
    summary.number("wall_shear_stress_error_" + face, loads[w].shear_stress_error);
    summary.number("wall_friction_" + face, loads[w].friction);
  }
}

}  // namespace grainflow::observe
