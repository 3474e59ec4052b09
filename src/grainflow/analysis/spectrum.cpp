#include "grainflow/analysis/spectrum.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <stdexcept>

#include "grainflow/analysis/fft.hpp"

namespace grainflow::analysis {

PowerSpectrum welch_psd(std::span<const double> x, double sample_interval, std::size_t segment_length) {
  if (sample_interval <= 0.0) throw std::invalid_argument("welch_psd: sample_interval must be positive");
  if (segment_length < 2 || segment_length > x.size())
    throw std::invalid_argument("welch_psd: segment_length must be in [2, series length]");
  const std::size_t L = segment_length, step = std::max<std::size_t>(1, L / 2), bins = L / 2 + 1;

  // Periodic Hann window: its half-overlapped copies sum to a constant, so every sample is
  // weighted alike away from the ends.
  std::vector<double> window(L);
  for (std::size_t j = 0; j < L; ++j) {
    const double s = std::sin(M_PI * static_cast<double>(j) / static_cast<double>(L));
    window[j] = s * s;
  }
  const double window_power = std::inner_product(window.begin(), window.end(), window.begin(), 0.0);

  RealFft fft(L);
  std::vector<double> segment(L);
  std::vector<std::complex<double>> spectrum(bins);
  PowerSpectrum out;
  out.density.assign(bins, 0.0);
  for (std::size_t start = 0; start + L <= x.size(); start += step) {
    const auto part = x.subspan(start, L);
    const double mean = std::accumulate(part.begin(), part.end(), 0.0) / static_cast<double>(L);
    for (std::size_t j = 0; j < L; ++j) segment[j] = window[j] * (part[j] - mean);
    fft.forward(segment, spectrum);
    for (std::size_t k = 0; k < bins; ++k) out.density[k] += std::norm(spectrum[k]);
    ++out.segments;
  }

  const double scale = sample_interval / (window_power * static_cast<double>(out.segments));
  out.frequency.resize(bins);
  out.resolution = 1.0 / (static_cast<double>(L) * sample_interval);
  for (std::size_t k = 0; k < bins; ++k) {
    const bool unpaired = k == 0 || (L % 2 == 0 && k == L / 2);  // bins without a negative twin
    out.density[k] *= (unpaired ? 1.0 : 2.0) * scale;
    out.frequency[k] = static_cast<double>(k) * out.resolution;
  }
  return out;
}

std::size_t peak_bin(const PowerSpectrum& s) {
  if (s.density.size() < 2) throw std::invalid_argument("peak_bin: the spectrum has no bin above zero frequency");
  return static_cast<std::size_t>(std::max_element(s.density.begin() + 1, s.density.end()) - s.density.begin());
}

double peak_frequency(const PowerSpectrum& s) { return s.frequency[peak_bin(s)]; }

}  // namespace grainflow::analysis
