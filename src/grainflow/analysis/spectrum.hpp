// Power spectral density of a uniformly sampled series by Welch's method (Welch 1967): the
// estimate of Lan's eq. (3-2-1) used in section 4.3 to find the frequencies of the zones' motion.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace grainflow::analysis {

struct PowerSpectrum {
  std::vector<double> frequency;  // Hz, f_k = k / (L dt), k = 0 .. L/2
  std::vector<double> density;    // x^2/Hz, one-sided: integral over [0, 1/(2 dt)] = variance
  double resolution = 0.0;        // Hz, bin width 1 / (L dt)
  std::size_t segments = 0;       // number of averaged segments
};

// Welch PSD: segments of `segment_length` L (2 <= L <= x.size()) overlapping by half (step L/2,
// rounded down; a tail shorter than a step is left out), each with its own mean removed and a
// periodic Hann window w_j = sin^2(pi j / L) applied, then
//   P_k = c_k dt / U |sum_j w_j (x_j - mean) exp(-2 pi i j k / L)|^2,  U = sum_j w_j^2,
// with c_k = 2 for 0 < k < L/2 (folding the negative frequencies) and 1 at k = 0 and k = L/2,
// averaged over the segments. Normalised so that sum_k P_k / (L dt) equals the window-weighted
// mean square of each segment (Parseval), i.e. the variance for a stationary series.
PowerSpectrum welch_psd(std::span<const double> x, double sample_interval, std::size_t segment_length);

// Frequency (Hz) of the largest density above zero frequency (the zero bin is distorted by the
// per-segment mean removal); the bin's centre, so exact to half a bin.
// Index of the largest bin above 0 Hz.
std::size_t peak_bin(const PowerSpectrum& spectrum);
double peak_frequency(const PowerSpectrum& spectrum);

}  // namespace grainflow::analysis
