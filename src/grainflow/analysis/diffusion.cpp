#include "grainflow/analysis/diffusion.hpp"
#include "grainflow/analysis/least_squares_line.hpp"

#include <cmath>
#include <numeric>
#include <stdexcept>

namespace grainflow::analysis {
namespace {

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

VacfIntegral diffusion_from_vacf(std::span<const double> vacf, double sample_interval) {
  require(!vacf.empty(), "diffusion_from_vacf: empty autocorrelation");
  require(sample_interval > 0.0, "diffusion_from_vacf: sample_interval must be positive");
  VacfIntegral out;
  out.running_integral.assign(vacf.size(), 0.0);
  for (std::size_t k = 1; k < vacf.size(); ++k)
    out.running_integral[k] = out.running_integral[k - 1] + 0.5 * sample_interval * (vacf[k - 1] + vacf[k]);
  out.coefficient = out.running_integral.back();
  return out;
}

MsdFit diffusion_from_msd(std::span<const double> msd, double sample_interval, std::size_t first_lag,
                          std::size_t last_lag, int dimensions) {
  require(sample_interval > 0.0, "diffusion_from_msd: sample_interval must be positive");
  require(dimensions >= 1, "diffusion_from_msd: dimensions must be at least 1");
  require(first_lag < last_lag && last_lag < msd.size(),
          "diffusion_from_msd: the window needs first_lag < last_lag < msd.size()");
  std::vector<double> lag_time;
  for (std::size_t k = first_lag; k <= last_lag; ++k) lag_time.push_back(static_cast<double>(k) * sample_interval);
  const LeastSquaresLine line = fit_least_squares_line(lag_time, msd.subspan(first_lag, last_lag - first_lag + 1));
  MsdFit fit;
  fit.first_lag = first_lag;
  fit.last_lag = last_lag;
  fit.slope = line.slope;
  fit.intercept = line.intercept;
  fit.coefficient = fit.slope / (2.0 * dimensions);
  return fit;
}

MsdFit diffusion_from_msd(std::span<const double> msd, double sample_interval, int dimensions) {
  require(msd.size() >= 3, "diffusion_from_msd: needs at least three lags");
  const std::size_t last = msd.size() - 1;
  return diffusion_from_msd(msd, sample_interval, last / 2, last, dimensions);
}

double total_diffusion(std::span<const double> component_coefficients) {
  require(!component_coefficients.empty(), "total_diffusion: no components");
  return std::accumulate(component_coefficients.begin(), component_coefficients.end(), 0.0) /
         static_cast<double>(component_coefficients.size());
}

double carnahan_starling_g0(double solids_fraction) {
  require(solids_fraction >= 0.0 && solids_fraction < 1.0, "carnahan_starling_g0: solids fraction must be in [0, 1)");
  const double hole = 1.0 - solids_fraction;
  return (2.0 - solids_fraction) / (2.0 * hole * hole * hole);
}

double savage_dai_diffusion(double diameter, double temperature, double restitution, double solids_fraction) {
  require(diameter > 0.0, "savage_dai_diffusion: diameter must be positive");
  require(temperature >= 0.0, "savage_dai_diffusion: temperature must be non-negative");
  require(restitution > -1.0 && restitution <= 1.0, "savage_dai_diffusion: restitution must be in (-1, 1]");
  require(solids_fraction > 0.0 && solids_fraction < 1.0, "savage_dai_diffusion: solids fraction must be in (0, 1)");
  return diameter * std::sqrt(M_PI * temperature) /
         (8.0 * (1.0 + restitution) * solids_fraction * carnahan_starling_g0(solids_fraction));
}

}  // namespace grainflow::analysis
