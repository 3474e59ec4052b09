#include "grainflow/run/trajectory_analysis.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <optional>
#include <vector>

#include "grainflow/analysis/correlation.hpp"
#include "grainflow/analysis/diffusion.hpp"
#include "grainflow/analysis/spectrum.hpp"
#include "grainflow/run/distribution_analysis.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/io/flat_json_reader.hpp"
#include "grainflow/io/json_writer.hpp"

namespace grainflow::run {
namespace {

namespace fs = std::filesystem;
using Series = std::vector<std::vector<double>>;

// One component of a [samples, particles, 3] array, as one series per particle.
Series component(const io::H5Array& a, std::size_t axis, std::size_t first, std::size_t stride) {
  const std::size_t samples = a.shape[0], particles = a.shape[1];
  Series out;
  for (std::size_t k = first; k < particles; k += stride) {
    std::vector<double> s(samples);
    for (std::size_t t = 0; t < samples; ++t) s[t] = a.values[(t * particles + k) * 3 + axis];
    out.push_back(std::move(s));
  }
  return out;
}

struct Estimates {
  std::vector<std::vector<double>> vacf, msd;   // per component, lags 0..max
  std::vector<analysis::VacfIntegral> running;  // per component: running integral and D
  double vacf_d[3], msd_d[3];                   // m^2/s per component
  std::size_t fit_first = 0, fit_last = 0;
};

Estimates estimate(const io::H5Array& velocity, const io::H5Array& position, std::size_t max_lag, double interval,
                   std::size_t first, std::size_t stride) {
  Estimates e;
  for (std::size_t a = 0; a < 3; ++a) {
    e.vacf.push_back(analysis::autocorrelation(component(velocity, a, first, stride), max_lag));
    e.msd.push_back(analysis::mean_square_displacement(component(position, a, first, stride), max_lag));
    e.running.push_back(analysis::diffusion_from_vacf(e.vacf[a], interval));
    e.vacf_d[a] = e.running[a].coefficient;
    const auto fit = analysis::diffusion_from_msd(e.msd[a], interval);
    e.msd_d[a] = fit.coefficient;
    e.fit_first = fit.first_lag;
    e.fit_last = fit.last_lag;
  }
  return e;
}

// Standard error of the mean of independent group estimates.
double standard_error(const std::vector<double>& values) {
  const double n = static_cast<double>(values.size());
  if (n < 2) return 0.0;
  double mean = 0.0, sum2 = 0.0;
  for (double v : values) mean += v / n;
  for (double v : values) sum2 += (v - mean) * (v - mean);
  return std::sqrt(sum2 / (n - 1.0) / n);
}

// zone_series.h5 -> analysis/zone_spectra.csv and analysis/floor_correlation.csv (Lan section 4.3):
// Welch spectra of the floor's and each zone's velocity along gravity, and the delay of each zone
// behind the floor from the peak of their cross-correlation, with the implied wave speed.
void analyze_zone_series(const fs::path& dir) {
  const fs::path file = dir / "zone_series.h5";
  const io::H5Reader h5(file.string());
  const io::H5Array u = h5.read("/zone_velocity");
  const io::H5Array floor_v = h5.read("/floor_velocity"), floor_x = h5.read("/floor_position");
  const std::vector<double> centre = h5.read("/zone_centre").values;
  const double interval = h5.number("/", "interval");
  const auto axis = static_cast<std::size_t>(h5.number("/", "gravity_axis"));
  const std::size_t samples = u.shape.empty() ? 0 : u.shape[0], zones = centre.size();
  if (samples < 16)
    throw InputError(file.string(), "samples", "holds " + std::to_string(samples) + " samples: too few for a spectrum");
  // Segments: the largest power of two up to a quarter of the record (7 half-overlapping segments
  // or more), so each spectrum is an average, not one noisy periodogram.
  std::size_t segment = 8;
  while (segment * 2 <= samples / 4) segment *= 2;
  std::vector<std::vector<double>> series(zones, std::vector<double>(samples));
  for (std::size_t t = 0; t < samples; ++t)
    for (std::size_t z = 0; z < zones; ++z) series[z][t] = u.values[(t * zones + z) * 3 + axis];
  const auto floor_spectrum = analysis::welch_psd(floor_v.values, interval, segment);
  std::vector<analysis::PowerSpectrum> spectra;
  for (const auto& s : series) spectra.push_back(analysis::welch_psd(s, interval, segment));
  io::write_atomically((dir / "analysis" / "zone_spectra.csv").string(), [&](std::ostream& out) {
    out << "# one-sided power spectral density (Welch, Hann, 50% overlap, " << segment << "-sample segments, "
        << floor_spectrum.segments << " segments) of the velocity along gravity: the floor and each zone's mean\n";
    out << "# units: frequency Hz, psd (m/s)^2/Hz; zone k is centred at analysis/floor_correlation.csv's height\n";
    out << "frequency,floor";
    for (std::size_t z = 0; z < zones; ++z) out << ",zone_" << z;
    out << '\n' << std::setprecision(10);
    for (std::size_t k = 0; k < floor_spectrum.frequency.size(); ++k) {
      out << floor_spectrum.frequency[k] << ',' << floor_spectrum.density[k];
      for (const auto& s : spectra) out << ',' << s.density[k];
      out << '\n';
    }
  });
  double floor_mean = 0.0;
  for (double x : floor_x.values) floor_mean += x / static_cast<double>(floor_x.values.size());
  // The zone's response to a periodic floor repeats every period: its delay is the first peak at a
  // lag in [0, one period) (Lan: the peak shifts right as the zone rises). Without a drive, the
  // largest peak within a quarter of the record.
  const double drive = h5.number("/", "drive_frequency");
  const std::size_t max_lag = samples / 4;
  const std::size_t period = drive > 0.0 ? static_cast<std::size_t>(std::ceil(1.0 / (drive * interval))) : 0;
  auto delay_of = [&](const std::vector<double>& c) {
    if (period == 0 || period > max_lag) return analysis::lag_of_maximum(c) * interval;
    std::size_t best = max_lag;
    for (std::size_t k = max_lag; k < max_lag + period; ++k)
      if (c[k] > c[best]) best = k;
    double shift = 0.0;  // parabola through the peak and its neighbours
    const double a = c[best - 1], b = c[best], d = c[best + 1], curvature = a - 2.0 * b + d;
    if (curvature < 0.0) shift = 0.5 * (a - d) / curvature;
    return (static_cast<double>(best) - static_cast<double>(max_lag) + shift) * interval;
  };
  io::write_atomically((dir / "analysis" / "floor_correlation.csv").string(), [&](std::ostream& out) {
    out << "# each zone's mean velocity along gravity against the floor's: lag of the cross-correlation peak"
           " (zone behind floor > 0; the first peak within one drive period), the implied wave speed"
           " = (zone centre - mean floor position) / delay, and the zone's spectral peak\n";
    out << "# units: height m (above the mean floor), delay s, speed m/s, peak_frequency Hz, peak_psd (m/s)^2/Hz\n";
    out << "zone,height,delay,speed,peak_frequency,peak_psd\n" << std::setprecision(10);
    for (std::size_t z = 0; z < zones; ++z) {
      const auto c = analysis::cross_correlation(floor_v.values, series[z], max_lag, true);
      const double delay = delay_of(c);
      const double height = centre[z] - floor_mean;
      const std::size_t peak = analysis::peak_bin(spectra[z]);
      out << z << ',' << height << ',' << delay << ','
          << (height > 0.0 ? analysis::propagation_speed(height, delay) : std::nan("")) << ','
          << spectra[z].frequency[peak] << ',' << spectra[z].density[peak] << '\n';
    }
  });
  std::cout << "zone series: spectra of " << zones << " zones and the floor, " << samples << " samples (written to "
            << (dir / "analysis").string() << "/zone_spectra.csv, floor_correlation.csv)\n";
}

void analyze_trajectory(const fs::path& dir, const AnalyzeOptions& options);

}  // namespace

int analyze_run(const std::string& output_directory, const AnalyzeOptions& options) {
  const fs::path dir(output_directory);
  const bool trajectory = fs::exists(dir / "trajectory.h5"), zone_series = fs::exists(dir / "zone_series.h5");
  if (!trajectory && !zone_series)
    throw InputError((dir / "trajectory.h5").string(), "trajectory",
                     "no trajectory.h5 or zone_series.h5 in this folder: add a [trajectory] or [zone_series] table to "
                     "the case (docs/CASE_FILES.md) and run it");
  fs::create_directories(dir / "analysis");
  if (trajectory && is_edmd_trajectory((dir / "trajectory.h5").string())) analyze_distributions(dir.string(), options);
  else if (trajectory) analyze_trajectory(dir, options);
  if (zone_series) analyze_zone_series(dir);
  return 0;
}

namespace {

void analyze_trajectory(const fs::path& dir, const AnalyzeOptions& options) {
  const fs::path file = dir / "trajectory.h5";
  const io::H5Reader h5(file.string());
  const io::H5Array velocity = h5.read("/velocity"), position = h5.read("/position");
  if (velocity.shape.size() != 3 || velocity.shape[2] != 3 || position.shape != velocity.shape)
    throw InputError(file.string(), "velocity", "expected [samples, particles, 3] arrays of equal shape");
  const std::size_t samples = velocity.shape[0], particles = velocity.shape[1];
  const double interval = h5.number("/", "window");
  const long long stored_lag = static_cast<long long>(h5.number("/", "max_lag"));
  const long long max_lag = options.max_lag > 0 ? options.max_lag : stored_lag;
  if (samples < 4 || particles == 0)
    throw InputError(file.string(), "samples",
                     "holds " + std::to_string(samples) + " samples of " + std::to_string(particles) +
                         " particles: too few to correlate");
  if (max_lag < 2 || max_lag >= static_cast<long long>(samples))
    throw InputError(file.string(), "max_lag",
                     std::to_string(max_lag) + " must lie in [2, samples = " + std::to_string(samples) + ")");
  const auto lags = static_cast<std::size_t>(max_lag);

  const Estimates all = estimate(velocity, position, lags, interval, 0, 1);
  // Error bars: the same estimators on independent groups of particles (every G-th particle).
  const int groups = static_cast<int>(std::min<std::size_t>(std::max(options.groups, 1), particles));
  std::vector<double> group_vacf[4], group_msd[4];
  if (groups >= 2) {
    for (int g = 0; g < groups; ++g) {
      const Estimates e = estimate(velocity, position, lags, interval, static_cast<std::size_t>(g), groups);
      for (int a = 0; a < 3; ++a) {
        group_vacf[a].push_back(e.vacf_d[a]);
        group_msd[a].push_back(e.msd_d[a]);
      }
      group_vacf[3].push_back((e.vacf_d[0] + e.vacf_d[1] + e.vacf_d[2]) / 3.0);
      group_msd[3].push_back((e.msd_d[0] + e.msd_d[1] + e.msd_d[2]) / 3.0);
    }
  }

  io::write_atomically((dir / "analysis" / "vacf.csv").string(), [&](std::ostream& out) {
    out << "# velocity autocorrelation <v_a(t + lag) v_a(t)> over " << particles << " particles and " << samples
        << " samples (Lan 1994 eq. 3-2-6, per component eq. 4-4-1), and its running integral D_a(lag) (eq. 4-4-2)\n";
    out << "# units: time s, vacf m^2/s^2, running_d m^2/s\n";
    out << "lag,time,vacf_x,vacf_y,vacf_z,vacf,running_d_x,running_d_y,running_d_z,running_d\n";
    const auto& running = all.running;
    out << std::setprecision(10);
    for (std::size_t k = 0; k <= lags; ++k) {
      const double sum = all.vacf[0][k] + all.vacf[1][k] + all.vacf[2][k];
      const double d =
          (running[0].running_integral[k] + running[1].running_integral[k] + running[2].running_integral[k]) / 3.0;
      out << k << ',' << k * interval << ',' << all.vacf[0][k] << ',' << all.vacf[1][k] << ',' << all.vacf[2][k] << ','
          << sum << ',' << running[0].running_integral[k] << ',' << running[1].running_integral[k] << ','
          << running[2].running_integral[k] << ',' << d << '\n';
    }
  });
  io::write_atomically((dir / "analysis" / "msd.csv").string(), [&](std::ostream& out) {
    out << "# mean-square displacement of unwrapped positions per component over " << particles
        << " particles (Lan 1994 eq. 3-3-7); msd = x + y + z\n";
    out << "# units: time s, msd m^2\n";
    out << "lag,time,msd_x,msd_y,msd_z,msd\n";
    out << std::setprecision(10);
    for (std::size_t k = 0; k <= lags; ++k)
      out << k << ',' << k * interval << ',' << all.msd[0][k] << ',' << all.msd[1][k] << ',' << all.msd[2][k] << ','
          << all.msd[0][k] + all.msd[1][k] + all.msd[2][k] << '\n';
  });
  io::JsonObject json;
  json.string("trajectory", file.string());
  json.integer("particles", static_cast<long long>(particles));
  json.integer("samples", static_cast<long long>(samples));
  json.number("sample_interval", interval);
  json.integer("max_lag", max_lag);
  json.integer("msd_fit_first_lag", static_cast<long long>(all.fit_first));
  json.integer("msd_fit_last_lag", static_cast<long long>(all.fit_last));
  json.integer("error_groups", groups >= 2 ? groups : 0);
  const char* names[4] = {"x", "y", "z", "total"};
  for (int a = 0; a < 4; ++a) {
    const double dv = a < 3 ? all.vacf_d[a] : (all.vacf_d[0] + all.vacf_d[1] + all.vacf_d[2]) / 3.0;
    const double dm = a < 3 ? all.msd_d[a] : (all.msd_d[0] + all.msd_d[1] + all.msd_d[2]) / 3.0;
    json.number(std::string("d_vacf_") + names[a], dv);
    json.number(std::string("d_vacf_") + names[a] + "_error", standard_error(group_vacf[a]));
    json.number(std::string("d_msd_") + names[a], dm);
    json.number(std::string("d_msd_") + names[a] + "_error", standard_error(group_msd[a]));
  }
  // Savage's kinetic-theory value (eqs. 4-3-3, 4-3-4) from the run's cell-average temperature and
  // bulk solids fraction, as Lan compared them in Table 4.5.
  std::optional<double> theory;
  const fs::path summary_path = dir / "summary.json";
  if (fs::exists(summary_path)) {
    double temperature = 0.0, fraction = 0.0;
    for (const auto& [key, value] : io::read_flat_json_file(summary_path.string())) {
      if (value.kind != io::FlatJsonValue::Kind::number) continue;
      if (key == "cell_temperature") temperature = std::stod(value.text);
      if (key == "bulk_solids_fraction") fraction = std::stod(value.text);
    }
    {
      const double diameter = h5.number("/", "diameter"), restitution = h5.number("/", "restitution");
      if (temperature > 0.0 && fraction > 0.0 && fraction < 1.0) {
        theory = analysis::savage_dai_diffusion(diameter, temperature, restitution, fraction);
        json.number("cell_temperature", temperature);
        json.number("bulk_solids_fraction", fraction);
        json.number("restitution", restitution);
        json.number("d_savage_dai", *theory);
      }
    }
  }
  io::write_atomically((dir / "analysis" / "diffusion.json").string(), [&](std::ostream& out) { json.write(out); });
  std::cout << std::setprecision(4) << "diffusion (m^2/s), from the VACF integral / the MSD slope:\n";
  for (int a = 0; a < 3; ++a)
    std::cout << "  D_" << names[a] << " = " << all.vacf_d[a] << " / " << all.msd_d[a] << "\n";
  std::cout << "  D = " << (all.vacf_d[0] + all.vacf_d[1] + all.vacf_d[2]) / 3.0 << " / "
            << (all.msd_d[0] + all.msd_d[1] + all.msd_d[2]) / 3.0 << "   (written to " << (dir / "analysis").string()
            << "/)\n";
  if (theory) std::cout << "  D (Savage-Dai kinetic theory, cell-average T and bulk nu) = " << *theory << "\n";
}

}  // namespace
}  // namespace grainflow::run
