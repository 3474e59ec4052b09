#include "grainflow/observe/strip_profile_observer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "grainflow/analysis/local_quadratic_fit.hpp"
#include "grainflow/analysis/open_channel.hpp"
#include "grainflow/io/atomic_file.hpp"

namespace grainflow::observe {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// A dense strip is a plug when its shear rate is below this fraction of the profile's mean one.
constexpr double kPlugShearFraction = 0.1;

std::string format(const char* pattern, double a, double b = 0.0, double c = 0.0) {
  char text[256];
  std::snprintf(text, sizeof text, pattern, a, b, c);
  return text;
}

}  // namespace

struct StripProfileObserver::Derived {
  std::vector<double> du_dy, du_dy_error, s_prose, s_listing, plug;
  double scaling = kNaN;  // Couette (H / U_T)^2, s^2
  // Chute.
  double depth = kNaN, mass_flow = kNaN, mass_per_width = kNaN, mean_velocity = kNaN, max_velocity = kNaN;
  double froude = kNaN, froude_normal = kNaN, critical_froude = kNaN, angle = kNaN;
  double max_velocity_error = kNaN;
  // Standard errors (block averages of the per-sample values; NaN with too few samples).
  double depth_error = kNaN, mass_flow_error = kNaN, mean_velocity_error = kNaN, froude_error = kNaN;
  analysis::ProfileParameters shape{kNaN, kNaN, kNaN, kNaN};
  // Couette: gap H and U_T, the top wall's x speed relative to the bottom's, means over the samples.
  double gap = kNaN, speed = kNaN;
  double slip = kNaN, slip_top = kNaN;  // m/s, the strip nearest the wall relative to the wall
  double slip_error = kNaN, slip_top_error = kNaN;
};

StripProfileObserver::StripProfileObserver(const RunContext& run, const Frame& s)
    : c_(*run.c),
      strips_(*run.c, s),
      profile_(s.dimension, strips_.count()),
      interval_(c_.output.profile_interval > 0.0 ? c_.output.profile_interval : c_.output.interval / 10.0),
      first_sample_(kNaN) {
  next_ = first_grid_index(s.time, interval_);
  bottom_wall_ = s.walls.with_role(WallRole::shear_bottom);
  top_wall_ = s.walls.with_role(WallRole::shear_top);
  chute_ = top_wall_ < 0 && c_.gravity.x != 0.0 && c_.gravity.y < 0.0;
}

void StripProfileObserver::sample(const Frame& s) {
  ++next_;
  if (!(s.time > c_.output.average_start) || s.collisions < c_.output.average_start_collisions) return;
  const StripGrid grid = strips_.grid_at(s, s.time);
  profile_.sample(*s.particles, grid);
  if (!std::isfinite(first_sample_)) first_sample_ = s.time;
  bottom_ = grid.lo();
  thickness_ = grid.thickness();
  cross_section_ = grid.cross_section();
  const ParticleStore& p = *s.particles;
  double mass = 0.0, moment = 0.0, momentum = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    mass += p.mass[i];
    moment += p.mass[i] * (p.position[i].y - grid.lo());
    momentum += p.mass[i] * p.velocity[i].x;
  }
  if (mass > 0.0) sum_height_ += moment / mass;
  bulk_blocks_.add({{mass > 0.0 ? moment / mass : 0.0, momentum, mass}});
  sum_gap_ += grid.hi() - grid.lo();
  if (bottom_wall_ >= 0) sum_bottom_speed_ += s.walls[bottom_wall_].velocity.x;
  if (top_wall_ >= 0) sum_top_speed_ += s.walls[top_wall_].velocity.x;
}

// Per strip: du/dy from the local quadratic fit, S in both forms, the plug-flow flag.
void StripProfileObserver::derive_strips(const std::vector<StripAverages>& strips, Derived& d) const {
  using namespace strip;
  const std::size_t n = strips.size();
  const double radius = 0.5 * c_.species.front().diameter;  // Campbell's R
  std::vector<double> y(n), velocity(n), velocity_error(n);
  for (std::size_t k = 0; k < n; ++k) {
    y[k] = strips[k].centre;
    velocity[k] = strips[k].value[u];
    velocity_error[k] = strips[k].error[u];
  }
  const auto fit = analysis::local_quadratic_fit(y, velocity, velocity_error);
  // The profile's mean shear rate, the reference for the plug-flow flag.
  double u_lo = INFINITY, u_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
  for (std::size_t k = 0; k < n; ++k)
    if (strips[k].has_mass()) {
      u_lo = std::min(u_lo, velocity[k]), u_hi = std::max(u_hi, velocity[k]);
      y_lo = std::min(y_lo, y[k]), y_hi = std::max(y_hi, y[k]);
    }
  const double mean_shear = y_hi > y_lo ? (u_hi - u_lo) / (y_hi - y_lo) : kNaN;
  const double shearable = profile_.dimension() == 2 ? kDiscSquarePacking : kSphereCubicPacking;
  for (std::size_t k = 0; k < n; ++k) {
    const auto& x = strips[k].value;
    d.du_dy.push_back(fit[k].slope);
    d.du_dy_error.push_back(fit[k].slope_error);
    d.s_prose.push_back(2.0 * radius * fit[k].slope / std::sqrt(x[u_variance]));
    d.s_listing.push_back(2.0 * radius * fit[k].slope / std::sqrt(x[u_variance] + x[v_variance]));
    const bool plug = x[solids_fraction] > shearable && std::fabs(fit[k].slope) < kPlugShearFraction * mean_shear;
    d.plug.push_back(plug ? 1.0 : 0.0);
  }
}

// Gap, U_T, (H/U_T)^2 and the slip at each wall.
void StripProfileObserver::derive_couette(const std::vector<StripAverages>& strips, Derived& d) const {
  const double samples = static_cast<double>(profile_.samples());
  d.gap = sum_gap_ / samples;
  const double bottom_speed = sum_bottom_speed_ / samples, top_speed = sum_top_speed_ / samples;
  d.speed = top_speed - bottom_speed;
  d.scaling = d.speed != 0.0 ? (d.gap / d.speed) * (d.gap / d.speed) : kNaN;
  d.slip = strips.front().value[strip::u] - bottom_speed;
  d.slip_top = top_speed - strips.back().value[strip::u];
  d.slip_error = strips.front().error[strip::u];
  d.slip_top_error = strips.back().error[strip::u];
}

// Depth, mass flow, Froude numbers, Appendix A's profile parameters, slip at the bottom.
void StripProfileObserver::derive_chute(const std::vector<StripAverages>& strips, Derived& d) const {
  using namespace strip;
  const double samples = static_cast<double>(profile_.samples());
  const Vec3 g = c_.gravity;
  const double g_magnitude = norm(g), g_normal = -g.y;
  d.angle = std::atan2(std::fabs(g.x), g_normal) * 180.0 / M_PI;
  d.depth = 2.0 * sum_height_ / samples;
  double momentum = 0.0, mass = 0.0;
  std::vector<analysis::ProfileStrip> column;
  for (const auto& strip : strips) {
    const auto& x = strip.value;
    const double height = strip.centre - bottom_;  // of the strip's centre above the bottom
    column.push_back({height - 0.5 * thickness_, height + 0.5 * thickness_, x[solids_fraction], x[u]});
    mass += x[strip::mass];
    if (!strip.has_mass()) continue;
    momentum += x[strip::mass] * x[u];
    if (height <= d.depth && !(x[u] <= d.max_velocity)) {  // (NaN at first)
      d.max_velocity = x[u];
      d.max_velocity_error = strip.error[u];
    }
  }
  d.mass_flow = momentum / cross_section_;
  d.mass_per_width = mass / cross_section_;
  d.mean_velocity = mass > 0.0 ? momentum / mass : kNaN;
  d.froude = d.mean_velocity / std::sqrt(g_magnitude * d.depth);
  d.froude_normal = d.mean_velocity / std::sqrt(g_normal * d.depth);
  d.shape = analysis::open_channel_profile_parameters(column, d.depth);
  d.critical_froude = analysis::critical_froude_number(d.shape, g_normal / g_magnitude);
  const double wall_speed = bottom_wall_ >= 0 ? sum_bottom_speed_ / samples : 0.0;
  d.slip = strips.front().value[u] - wall_speed;
  d.slip_error = strips.front().error[u];
  // Errors: each block's mean height, momentum per width and momentum / mass.
  std::vector<double> height, flow, velocity;
  for (const auto& block : bulk_blocks_.blocks()) {
    const double n = static_cast<double>(bulk_blocks_.block_length());
    height.push_back(block[0].height / n);
    flow.push_back(block[0].momentum / n / cross_section_);
    velocity.push_back(block[0].mass > 0.0 ? block[0].momentum / block[0].mass : kNaN);
  }
  d.depth_error = 2.0 * blocked_standard_error(height);
  d.mass_flow_error = blocked_standard_error(flow);
  d.mean_velocity_error = blocked_standard_error(velocity);
  // Fr = u / sqrt(g H): relative errors add in quadrature, H's at half weight.
  d.froude_error =
      std::fabs(d.froude) * std::hypot(d.mean_velocity_error / d.mean_velocity, 0.5 * d.depth_error / d.depth);
}

std::vector<StripKinematics> StripProfileObserver::strip_kinematics() const {
  const auto strips = profile_.averages();
  Derived d;
  derive_strips(strips, d);
  std::vector<StripKinematics> result;
  for (std::size_t k = 0; k < strips.size(); ++k)
    result.push_back({strips[k], d.du_dy[k], d.du_dy_error[k], d.plug[k] != 0.0});
  return result;
}

void StripProfileObserver::write(const Frame&, OutputSink& out) {
  const std::string& dir = out.directory;
  io::JsonObject& summary = *out.summary;
  std::vector<std::string>& warnings = *out.warnings;
  using namespace strip;
  const auto strips = profile_.averages();
  Derived d;
  derive_strips(strips, d);
  if (profile_.samples() > 0 && strips_.between_walls()) derive_couette(strips, d);
  if (profile_.samples() > 0 && chute_) derive_chute(strips, d);
  const int dim = profile_.dimension();
  const bool couette = strips_.between_walls();
  const double radius = 0.5 * c_.species.front().diameter;
  const double g = norm(c_.gravity);
  if (profile_.samples() == 0)
    warnings.push_back("profiles.csv has no samples: the long-term averages never began (output.average_start " +
                       format("%g s", c_.output.average_start) + ", average_start_collisions " +
                       std::to_string(c_.output.average_start_collisions) + ")");

  // The columns, each a name and one value per strip; an average is followed by its error.
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  auto column = [&](const std::string& name, auto&& get) {
    names.push_back(name);
    columns.emplace_back();
    for (std::size_t k = 0; k < strips.size(); ++k) columns.back().push_back(get(k));
  };
  auto average = [&](const std::string& name, int q, double scale = 1.0) {
    column(name, [&](std::size_t k) { return strips[k].value[q] * scale; });
    column(name + "_error", [&](std::size_t k) { return strips[k].error[q] * scale; });
  };
  column("strip", [](std::size_t k) { return static_cast<double>(k); });
  column("y", [&](std::size_t k) { return strips[k].centre; });
  if (couette) column("y_over_gap", [&](std::size_t k) { return strips[k].relative_centre; });
  else if (chute_) column("y_over_H", [&](std::size_t k) { return (strips[k].centre - bottom_) / d.depth; });
  average("solids_fraction", solids_fraction);
  average("particles", particles);
  average("u", u);
  average("v", v);
  if (dim == 3) average("w", w);
  if (dim == 2) {
    average("omega", omega_z);
  } else {
    average("omega_x", omega_x);
    average("omega_y", omega_y);
    average("omega_z", omega_z);
  }
  average("u_variance", u_variance);
  average("v_variance", v_variance);
  if (dim == 3) average("w_variance", w_variance);
  average("uv_covariance", uv_covariance);
  average("rotational_temperature", rotational_temperature);
  average("granular_temperature", granular_temperature);
  average("temperature", temperature);
  average("translational_temperature", translational_temperature);
  average("temperature_lan", temperature_lan);
  if (couette) {
    average("u_variance_scaled", u_variance, d.scaling);
    average("v_variance_scaled", v_variance, d.scaling);
    if (dim == 3) average("w_variance_scaled", w_variance, d.scaling);
    average("rotational_temperature_scaled", rotational_temperature, d.scaling);
    average("granular_temperature_scaled", granular_temperature, d.scaling);
  }
  column("du_dy", [&](std::size_t k) { return d.du_dy[k]; });
  column("du_dy_error", [&](std::size_t k) { return d.du_dy_error[k]; });
  column("S_prose", [&](std::size_t k) { return d.s_prose[k]; });
  column("S_listing", [&](std::size_t k) { return d.s_listing[k]; });
  column("plug_flow", [&](std::size_t k) { return d.plug[k]; });

  io::write_atomically(dir + "/profiles.csv", [&](std::ostream& out) {
    out.precision(10);
    out << "# strip profiles (Campbell 1982 sections 3.1-3.2): " << profile_.samples() << " samples every " << interval_
        << " s from t = " << first_sample_ << " s; " << strips.size() << " strips along y";
    if (couette) out << " between the walls, stretching with them";
    out << "\n";
    if (couette)
      out << "# couette: mean gap H = " << d.gap << " m, U_T = " << d.speed
          << " m/s (top wall relative to bottom), (H/U_T)^2 = " << d.scaling << " s^2\n";
    if (chute_)
      out << "# chute: flow depth H = " << d.depth
          << " m (twice the mass-mean height above the bottom at y = " << bottom_ << " m), mean velocity "
          << d.mean_velocity << " m/s, Fr = " << d.froude << "\n";
    out << "# packing limits of sheared discs (section 3.1.7): triangular " << kDiscTriangularPacking
        << ", contour-following " << kDiscContourShearPacking << ", square " << kDiscSquarePacking
        << "; spheres' simple cubic " << kSphereCubicPacking << "\n";
    out << "# units: y m, velocities m/s, omega rad/s, *_variance, uv_covariance, rotational_temperature, "
           "granular_temperature, temperature_lan m^2/s^2, temperature and translational_temperature J per particle, "
           "*_scaled 1 (times (H/U_T)^2), du_dy 1/s, S 1; *_error: standard errors by block averaging (nan: too few "
           "samples)\n";
    for (std::size_t i = 0; i < names.size(); ++i) out << (i ? "," : "") << names[i];
    out << "\n";
    for (std::size_t k = 0; k < strips.size(); ++k) {
      for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << columns[i][k];
      out << "\n";
    }
  });

  summary.integer("profile_samples", profile_.samples());
  summary.integer("profile_strips", static_cast<long long>(strips.size()));
  // Campbell's per-run S (COL002's "AVERAGE R", Figs. 3.40-3.41): the listing's S averaged over
  // every strip with particles, the wall strips included; beside it the middle strip's.
  double s_sum = 0.0;
  long s_count = 0;
  for (double s : d.s_listing)
    if (std::isfinite(s)) s_sum += s, ++s_count;
  summary.number("S_listing_strip_mean", s_count > 0 ? s_sum / s_count : kNaN);
  summary.number("S_listing_middle_strip", d.s_listing.empty() ? kNaN : d.s_listing[d.s_listing.size() / 2]);
  if (chute_) {
    summary.number("chute_angle", d.angle);
    summary.number("flow_depth", d.depth);
    summary.number("flow_depth_error", d.depth_error);
    summary.number("mass_flow_per_width", d.mass_flow);
    summary.number("mass_flow_per_width_error", d.mass_flow_error);
    summary.number("mass_per_width", d.mass_per_width);
    summary.number("mean_velocity", d.mean_velocity);
    summary.number("mean_velocity_error", d.mean_velocity_error);
    summary.number("depth_mean_velocity", d.shape.depth_mean_velocity);
    summary.number("max_velocity", d.max_velocity);
    summary.number("froude_number", d.froude);
    summary.number("froude_number_error", d.froude_error);
    summary.number("froude_number_normal", d.froude_normal);
    summary.number("mean_solids_fraction", d.shape.mean_solids_fraction);
    summary.number("momentum_coefficient_gamma", d.shape.gamma);
    summary.number("pressure_coefficient_Gamma", d.shape.Gamma);
    summary.number("critical_froude_number", d.critical_froude);
    const bool known = std::isfinite(d.froude) && std::isfinite(d.critical_froude);
    summary.string("flow_regime", !known ? "unknown" : d.froude > d.critical_froude ? "supercritical" : "subcritical");
    summary.number("slip_velocity", d.slip);
    summary.number("slip_velocity_error", d.slip_error);
    summary.number("slip_fraction", d.slip / d.max_velocity);
    summary.number("slip_fraction_error", std::hypot(d.slip_error, d.slip / d.max_velocity * d.max_velocity_error) /
                                              std::fabs(d.max_velocity));
    summary.number("slip_velocity_scaled", d.slip / std::sqrt(g * radius));
  }
  if (couette) {
    summary.number("mean_gap", d.gap);
    summary.number("shear_speed", d.speed);
    summary.number("slip_velocity_bottom", d.slip);
    summary.number("slip_velocity_bottom_error", d.slip_error);
    summary.number("slip_velocity_top", d.slip_top);
    summary.number("slip_velocity_top_error", d.slip_top_error);
    summary.number("slip_fraction_bottom", d.slip / d.speed);
    summary.number("slip_fraction_bottom_error", d.slip_error / std::fabs(d.speed));
    summary.number("slip_fraction_top", d.slip_top / d.speed);
    summary.number("slip_fraction_top_error", d.slip_top_error / std::fabs(d.speed));
  }
}

}  // namespace grainflow::observe
