// Time-correlation functions of uniformly sampled series (Lan 1994 section 3.2, eqs. 3-2-2b,
// 3-2-3, 3-2-6) and the mean-square displacement (section 3.3, eq. 3-3-7), all by FFT in
// O(n log n), averaged over many series (one per particle) the way eq. (3-2-6) averages.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace grainflow::analysis {

// Unbiased autocorrelation C(k) = 1/(n-k) sum_{i=0}^{n-1-k} x_i x_{i+k}, k = 0 .. max_lag
// (max_lag < n). Every lag is the mean of all the products it has, so C(k) estimates
// <x(t) x(t+k dt)> without the (n-k)/n taper of the biased estimator; the price is a noisier
// tail when max_lag approaches n (Lan keeps max_lag <= n/2, section 3.2). With subtract_mean the
// series' own mean is removed first (the autocovariance).
std::vector<double> autocorrelation(std::span<const double> x, std::size_t max_lag, bool subtract_mean = false);

// The same over an ensemble of series, the average of eq. (3-2-6) over particles and time origins:
// C(k) = sum_s sum_i x_{s,i} x_{s,i+k} / sum_s (n_s - k), every product weighted alike (for
// series of equal length this is the plain mean of the per-series C(k)). Each series must be
// longer than max_lag; with subtract_mean each series loses its own mean.
std::vector<double> autocorrelation(std::span<const std::vector<double>> series, std::size_t max_lag,
                                    bool subtract_mean = false);

// Cross-correlation C_xy(k) = 1/(n-|k|) sum_i x_i y_{i+k} (eq. 3-2-3 with the unbiased
// normalisation) for k = -max_lag .. +max_lag, stored at index max_lag + k. x and y have the same
// length n > max_lag. A positive k means y follows x: if y(t) = x(t - delay), C_xy peaks at
// k = delay / dt. With x the floor velocity and y a zone's mean velocity, the peak lag is the
// zone's delay behind the floor (Lan section 4.3, Figs. A4.14).
std::vector<double> cross_correlation(std::span<const double> x, std::span<const double> y, std::size_t max_lag,
                                      bool subtract_mean = false);

// Lag (in samples, fractional) of the maximum of a cross-correlation laid out as above (odd size
// 2 max_lag + 1): the index of the largest value, refined by the vertex of the parabola through it
// and its two neighbours (no refinement at either end, or where the three points are not concave).
double lag_of_maximum(std::span<const double> cross_correlation);

// Speed of a disturbance that covers `distance` (m) in `delay` (s), e.g. a zone's height above the
// floor over its delay from lag_of_maximum * dt. NaN when delay <= 0 (no measurable delay).
double propagation_speed(double distance, double delay);

// Mean-square displacement MSD(k) = 1/(n-k) sum_{i=0}^{n-1-k} (x_{i+k} - x_i)^2, k = 0 .. max_lag
// (max_lag < n), of one coordinate of unwrapped positions (never reflected back into the periodic
// cell, Lan section 3.3). Computed as S1(k) - 2 S2(k), S2 the unbiased autocorrelation of x and
// S1(k) = 1/(n-k) sum_{i=0}^{n-1-k} (x_i^2 + x_{i+k}^2) by a running sum (Kneller et al. 1995;
// Calandrini et al. 2011, nMoldyn). The series' mean is subtracted first: the MSD does not change,
// and the cancellation in S1 - 2 S2 acts on the displacements' scale, not the positions'.
std::vector<double> mean_square_displacement(std::span<const double> x, std::size_t max_lag);

// The same over an ensemble (one series per particle), pooled like the autocorrelation: every
// displacement weighted alike. Eq. (3-3-7) then sums the components: MSD_r = MSD_x + MSD_y + MSD_z.
std::vector<double> mean_square_displacement(std::span<const std::vector<double>> series, std::size_t max_lag);

}  // namespace grainflow::analysis
