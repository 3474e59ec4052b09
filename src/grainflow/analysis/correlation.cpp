#include "grainflow/analysis/correlation.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "grainflow/analysis/fft.hpp"

namespace grainflow::analysis {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

std::vector<double> copy_centred(std::span<const double> x, bool subtract_mean) {
  std::vector<double> out(x.begin(), x.end());
  if (subtract_mean && !out.empty()) {
    const double mean = std::accumulate(out.begin(), out.end(), 0.0) / static_cast<double>(out.size());
    for (double& v : out) v -= mean;
  }
  return out;
}

// Raw lag sums R(k) = sum_s sum_i x_{s,i} x_{s,i+k}, k = 0 .. max_lag, over an ensemble. The
// transform length m >= n_max + max_lag keeps the circular correlation free of wrap-around: a
// product x_i x_{(i+k) mod m} that wraps needs i >= m - k >= n, where x is zero. Because the
// inverse transform is linear, the power spectra of all series are summed first and transformed
// back once.
class LagSums {
 public:
  LagSums(std::size_t longest, std::size_t max_lag)
      : fft_(good_fft_size(longest + max_lag)), spectrum_(fft_.spectrum_size()), power_(fft_.spectrum_size(), 0.0) {}

  void add(std::span<const double> x) {
    fft_.forward(x, spectrum_);
    for (std::size_t k = 0; k < power_.size(); ++k) power_[k] += std::norm(spectrum_[k]);
  }

  std::vector<double> sums(std::size_t max_lag) {
    std::vector<std::complex<double>> power(power_.begin(), power_.end());
    std::vector<double> out(max_lag + 1);
    fft_.inverse(power, out);
    const double scale = 1.0 / static_cast<double>(fft_.size());  // FFTW's inverse is unnormalised
    for (double& v : out) v *= scale;
    return out;
  }

 private:
  RealFft fft_;
  std::vector<std::complex<double>> spectrum_;
  std::vector<double> power_;
};

std::size_t check_ensemble(std::span<const std::vector<double>> series, std::size_t max_lag, const char* who) {
  require(!series.empty(), std::string(who) + ": no series");
  std::size_t longest = 0;
  for (const auto& s : series) {
    require(s.size() > max_lag, std::string(who) + ": every series must be longer than max_lag (" +
                                    std::to_string(max_lag) + "), one has " + std::to_string(s.size()));
    longest = std::max(longest, s.size());
  }
  return longest;
}

}  // namespace

std::vector<double> autocorrelation(std::span<const double> x, std::size_t max_lag, bool subtract_mean) {
  require(x.size() > max_lag, "autocorrelation: the series must be longer than max_lag");
  const std::vector<double> v = copy_centred(x, subtract_mean);
  LagSums sums(v.size(), max_lag);
  sums.add(v);
  std::vector<double> c = sums.sums(max_lag);
  for (std::size_t k = 0; k <= max_lag; ++k) c[k] /= static_cast<double>(v.size() - k);
  return c;
}

std::vector<double> autocorrelation(std::span<const std::vector<double>> series, std::size_t max_lag,
                                    bool subtract_mean) {
  LagSums sums(check_ensemble(series, max_lag, "autocorrelation"), max_lag);
  std::vector<double> count(max_lag + 1, 0.0);
  for (const auto& s : series) {
    sums.add(copy_centred(s, subtract_mean));
    for (std::size_t k = 0; k <= max_lag; ++k) count[k] += static_cast<double>(s.size() - k);
  }
  std::vector<double> c = sums.sums(max_lag);
  for (std::size_t k = 0; k <= max_lag; ++k) c[k] /= count[k];
  return c;
}

std::vector<double> cross_correlation(std::span<const double> x, std::span<const double> y, std::size_t max_lag,
                                      bool subtract_mean) {
  require(x.size() == y.size(), "cross_correlation: the two series must have the same length");
  require(x.size() > max_lag, "cross_correlation: the series must be longer than max_lag");
  const std::size_t n = x.size();
  const std::vector<double> xc = copy_centred(x, subtract_mean), yc = copy_centred(y, subtract_mean);
  // m >= n + max_lag: positive lags k land at index k, negative ones at m - |k|, and neither wraps
  // onto the other (same argument as for LagSums).
  RealFft fft(good_fft_size(n + max_lag));
  const std::size_t m = fft.size();
  std::vector<std::complex<double>> fx(fft.spectrum_size()), fy(fft.spectrum_size());
  fft.forward(xc, fx);
  fft.forward(yc, fy);
  for (std::size_t k = 0; k < fx.size(); ++k) fx[k] = std::conj(fx[k]) * fy[k];  // sum_i x_i y_{i+k}
  std::vector<double> circular(m);
  fft.inverse(fx, circular);
  std::vector<double> c(2 * max_lag + 1);
  for (std::size_t k = 0; k <= max_lag; ++k) {
    const double norm = 1.0 / (static_cast<double>(m) * static_cast<double>(n - k));
    c[max_lag + k] = circular[k] * norm;
    if (k > 0) c[max_lag - k] = circular[m - k] * norm;
  }
  return c;
}

double lag_of_maximum(std::span<const double> c) {
  require(c.size() % 2 == 1, "lag_of_maximum: expects 2 max_lag + 1 values, lags -max_lag .. +max_lag");
  const std::size_t max_lag = c.size() / 2;
  const std::size_t i = static_cast<std::size_t>(std::max_element(c.begin(), c.end()) - c.begin());
  double lag = static_cast<double>(i) - static_cast<double>(max_lag);
  if (i > 0 && i + 1 < c.size()) {
    const double left = c[i - 1], mid = c[i], right = c[i + 1];
    const double curvature = left - 2.0 * mid + right;
    // Vertex of the parabola through the three points; |offset| <= 1/2 because mid is the largest.
    if (curvature < 0.0) lag += 0.5 * (left - right) / curvature;
  }
  return lag;
}

double propagation_speed(double distance, double delay) {
  return delay > 0.0 ? distance / delay : std::numeric_limits<double>::quiet_NaN();
}

std::vector<double> mean_square_displacement(std::span<const double> x, std::size_t max_lag) {
  const std::vector<double> one(x.begin(), x.end());
  return mean_square_displacement(std::span<const std::vector<double>>(&one, 1), max_lag);
}

std::vector<double> mean_square_displacement(std::span<const std::vector<double>> series, std::size_t max_lag) {
  LagSums products(check_ensemble(series, max_lag, "mean_square_displacement"), max_lag);
  std::vector<double> square_sums(max_lag + 1, 0.0), count(max_lag + 1, 0.0);
  std::vector<double> prefix;
  for (const auto& s : series) {
    const std::vector<double> v = copy_centred(s, true);
    const std::size_t n = v.size();
    products.add(v);
    // S1 numerator sum_{i<n-k} x_i^2 + sum_{i>=k} x_i^2 from prefix sums P(j) = sum_{i<j} x_i^2.
    prefix.assign(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + v[i] * v[i];
    for (std::size_t k = 0; k <= max_lag; ++k) {
      square_sums[k] += prefix[n - k] + (prefix[n] - prefix[k]);
      count[k] += static_cast<double>(n - k);
    }
  }
  const std::vector<double> s2 = products.sums(max_lag);
  std::vector<double> msd(max_lag + 1);
  for (std::size_t k = 0; k <= max_lag; ++k) msd[k] = (square_sums[k] - 2.0 * s2[k]) / count[k];
  msd[0] = 0.0;  // exactly, rather than the round-off of S1(0) - 2 S2(0)
  return msd;
}

}  // namespace grainflow::analysis
