#include "grainflow/app/analyze_command.hpp"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <vector>

#include "grainflow/analysis/correlation.hpp"
#include "grainflow/analysis/diffusion.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/io/atomic_file.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/io/json_writer.hpp"

namespace grainflow::app {
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
  std::vector<std::vector<double>> vacf, msd;  // per component, lags 0..max
  double vacf_d[3], msd_d[3];                  // m^2/s per component
  std::size_t fit_first = 0, fit_last = 0;
};

Estimates estimate(const io::H5Array& velocity, const io::H5Array& position, std::size_t max_lag, double interval,
                   std::size_t first, std::size_t stride) {
  Estimates e;
  for (std::size_t a = 0; a < 3; ++a) {
    e.vacf.push_back(analysis::autocorrelation(component(velocity, a, first, stride), max_lag));
    e.msd.push_back(analysis::mean_square_displacement(component(position, a, first, stride), max_lag));
    e.vacf_d[a] = analysis::diffusion_from_vacf(e.vacf[a], interval).coefficient;
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

}  // namespace

int analyze_run(const std::string& output_directory, const AnalyzeOptions& options) {
  const fs::path dir(output_directory);
  const fs::path file = dir / "trajectory.h5";
  if (!fs::exists(file))
    throw InputError(file.string(), "trajectory",
                     "no trajectory.h5 in this folder: add a [trajectory] table to the case (docs/CASE_FILES.md) and run it");
  const io::H5Reader h5(file.string());
  const io::H5Array velocity = h5.read("/velocity"), position = h5.read("/position");
  if (velocity.shape.size() != 3 || velocity.shape[2] != 3 || position.shape != velocity.shape)
    throw InputError(file.string(), "velocity", "expected [samples, particles, 3] arrays of equal shape");
  const std::size_t samples = velocity.shape[0], particles = velocity.shape[1];
  const double interval = h5.number("/", "window");
  const long long stored_lag = static_cast<long long>(h5.number("/", "max_lag"));
  const long long max_lag = options.max_lag > 0 ? options.max_lag : stored_lag;
  if (samples < 4 || particles == 0)
    throw InputError(file.string(), "samples", "holds " + std::to_string(samples) + " samples of " +
                                                   std::to_string(particles) + " particles: too few to correlate");
  if (max_lag < 2 || max_lag >= static_cast<long long>(samples))
    throw InputError(file.string(), "max_lag", std::to_string(max_lag) + " must lie in [2, samples = " +
                                                   std::to_string(samples) + ")");
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

  fs::create_directories(dir / "analysis");
  io::write_atomically((dir / "analysis" / "vacf.csv").string(), [&](std::ostream& out) {
    out << "# velocity autocorrelation <v_a(t + lag) v_a(t)> over " << particles << " particles and " << samples
        << " samples (Lan 1994 eq. 3-2-6, per component eq. 4-4-1), and its running integral D_a(lag) (eq. 4-4-2)\n";
    out << "# units: time s, vacf m^2/s^2, running_d m^2/s\n";
    out << "lag,time,vacf_x,vacf_y,vacf_z,vacf,running_d_x,running_d_y,running_d_z,running_d\n";
    std::vector<analysis::VacfIntegral> running;
    for (int a = 0; a < 3; ++a) running.push_back(analysis::diffusion_from_vacf(all.vacf[a], interval));
    out << std::setprecision(10);
    for (std::size_t k = 0; k <= lags; ++k) {
      const double sum = all.vacf[0][k] + all.vacf[1][k] + all.vacf[2][k];
      const double d = (running[0].running_integral[k] + running[1].running_integral[k] + running[2].running_integral[k]) / 3.0;
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
  io::write_atomically((dir / "analysis" / "diffusion.json").string(), [&](std::ostream& out) { json.write(out); });
  std::cout << std::setprecision(4) << "diffusion (m^2/s), from the VACF integral / the MSD slope:\n";
  for (int a = 0; a < 3; ++a)
    std::cout << "  D_" << names[a] << " = " << all.vacf_d[a] << " / " << all.msd_d[a] << "\n";
  std::cout << "  D = " << (all.vacf_d[0] + all.vacf_d[1] + all.vacf_d[2]) / 3.0 << " / "
            << (all.msd_d[0] + all.msd_d[1] + all.msd_d[2]) / 3.0 << "   (written to "
            << (dir / "analysis").string() << "/)\n";
  return 0;
}

}  // namespace grainflow::app
