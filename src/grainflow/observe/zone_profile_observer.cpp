#include "grainflow/observe/zone_profile_observer.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/io/atomic_file.hpp"

namespace grainflow::observe {

ZoneLayout::ZoneLayout(const RunContext& run) : axis(run.gravity_axis) {
  const CaseConfig& c = *run.c;
  thickness = c.output.zone_thickness > 0.0 ? c.output.zone_thickness : run.reference_diameter;
  for (int a = 0; a < run.dimension; ++a)
    if (a != axis) area *= c.domain.length(a);
  lo = c.domain.lo[axis];
  if (c.drive.enabled && c.drive.face == axis * 2)
    lo -= thickness * std::ceil(c.drive.amplitude[axis] / thickness - 1e-9);
  hi = c.domain.hi[axis];
}

ZoneProfile ZoneLayout::profile(const RunContext& run) const {
  ZoneProfile p(axis, lo, hi, thickness, area, run.dimension);
  p.set_reduce(run.ranks);
  const CaseConfig& c = *run.c;
  // Lees-Edwards images slide along x across the y faces only.
  if (c.domain.periodic(axis)) p.set_period(Vec3{axis == 1 ? c.lees_edwards_rate * (hi - lo) : 0.0, 0.0, 0.0});
  return p;
}

ZoneProfileObserver::ZoneProfileObserver(const RunContext& run)
    : run_(run),
      profile_(ZoneLayout(run).profile(run)),
      schedule_(run.c->output.profile_interval > 0.0 ? run.c->output.profile_interval : run.c->output.interval / 10.0,
                run.time_step),
      average_from_(static_cast<long>(std::ceil(run.c->output.average_start / run.time_step - 1e-9))) {}

void ZoneProfileObserver::write(const Frame& last, OutputSink& out) {
  (void)last;
  const double diameter = run_.reference_diameter;
  const double g = norm(run_.c->gravity);
  const auto zones = profile_.averages();
  if (out.writes)
    io::write_atomically(out.directory + "/profiles.csv", [&](std::ostream& file) {
      file << "# zone profiles along the gravity axis, long-term averages over " << profile_.samples()
           << " samples; temperature = about the instantaneous zone mean (Lan), temperature_time_mean = about the"
              " long-term zone mean (Campbell)\n";
      file << "# units: position m, Y 1 (position / d), velocities m/s, temperatures m^2/s^2, W 1 (sqrt(T/(g d))), "
              "kinetic_energy_density J/m^"
           << run_.dimension << "; *_error: standard errors by block averaging (nan: too few samples)\n";
      file << "zone,position_lo,position_hi,position,Y,solids_fraction,mean_velocity_x,mean_velocity_y,mean_velocity_z,"
              "temperature_x,temperature_y,temperature_z,temperature,temperature_time_mean,W,kinetic_energy_density,"
              "solids_fraction_error,mean_velocity_y_error,temperature_error,temperature_time_mean_error,W_error\n";
      for (std::size_t z = 0; z < zones.size(); ++z) {
        const auto& a = zones[z];
        const double mid = 0.5 * (a.lo + a.hi);
        const int dim = run_.dimension;  // the components in the plane of motion (z is 0 in 2D)
        const double t = (a.temperature_lan.x + a.temperature_lan.y + a.temperature_lan.z) / dim;
        const double tm = (a.temperature_time_mean.x + a.temperature_time_mean.y + a.temperature_time_mean.z) / dim;
        const double w = g > 0.0 ? std::sqrt(t / (g * diameter)) : 0.0;
        // dW = dT / (2 sqrt(T g d)), first-order propagation.
        const double w_error = t > 0.0 && g > 0.0 ? a.temperature_lan_error / (2.0 * std::sqrt(t * g * diameter)) : NAN;
        file << z << ',' << a.lo << ',' << a.hi << ',' << mid << ',' << mid / diameter << ',' << a.solids_fraction
             << ',' << a.mean_velocity.x << ',' << a.mean_velocity.y << ',' << a.mean_velocity.z << ','
             << a.temperature_lan.x << ',' << a.temperature_lan.y << ',' << a.temperature_lan.z << ',' << t << ',' << tm
             << ',' << w << ',' << a.kinetic_energy_density << ',' << a.solids_fraction_error << ','
             << a.mean_velocity_error.y << ',' << a.temperature_lan_error << ',' << a.temperature_time_mean_error << ','
             << w_error << '\n';
      }
    });
  out.summary->integer("profile_samples", profile_.samples());
  // Height of the long-term density peak above the floor's rest position, in diameters (Fig. A4.8).
  if (!zones.empty() && profile_.samples() > 0) {
    const auto peak = std::max_element(
        zones.begin(), zones.end(), [](const auto& a, const auto& b) { return a.solids_fraction < b.solids_fraction; });
    out.summary->number("density_peak_Y",
                        (0.5 * (peak->lo + peak->hi) - run_.c->domain.lo[run_.gravity_axis]) / diameter);
  }
}

}  // namespace grainflow::observe
