// When did a run become steady? Campbell 1982 section 2.5 judges convergence by the total kinetic
// energy: once energy input and dissipation balance, it fluctuates about a constant mean. The
// detector makes that judgement objective. For each candidate start s (every `step_fraction` of the
// series) it tests the remaining series x[s..n) for drift:
//  - linear trend: the least-squares slope b over the remainder against its error
//    sigma_b = sqrt(S / sum (t - t_mean)^2);
//  - halves: the difference of the means of the remainder's two halves against sqrt(2 S / m),
//    m samples per half (catches a change that a line misses).
// S is the noise's long-run variance per sample (variance times integrated autocorrelation time),
// m se^2 with se the Flyvbjerg-Petersen standard error of the mean of the *later half*, detrended:
// correlated fluctuations are then not mistaken for drift, and an early transient, which would
// inflate an estimate from the whole remainder and hide itself, stays out of it.
// The run is steady from the earliest candidate passing both tests at |z| < z_max. The remainder
// keeps at least `min_fraction` of the series and `min_samples` samples, so a series that settles
// only in its last few samples counts as not converged. z_max = 4 allows for the uncertainty of S
// estimated from a few hundred samples: on stationary AR(1) noise (3000 samples) a false "not yet
// steady" at the first candidate came in 0 of 300 series with correlation time 10 samples and in
// 10 of 300 with 50 (30 of 300 at z_max = 3). A transient A exp(-t/tau) in white noise sigma
// (t, tau in samples, n_rest >> tau samples left) gives z = sqrt(3) (A exp(-s/tau) / sigma)
// tau / sqrt(n_rest): the start is found where the transient has sunk to 2.3 sigma sqrt(n_rest) / tau
// (A/sigma = 20, tau = 100, 2000 samples: at 250-450 over 300 series, the noise level at 300).
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>

namespace grainflow::analysis {

struct SteadyStateOptions {
  double z_max = 4.0;            // drift significant beyond this many standard errors
  double step_fraction = 0.025;  // candidate starts every 2.5 % of the series
  double min_fraction = 0.2;     // the steady remainder is at least a fifth of the series ...
  std::size_t min_samples = 32;  // ... and at least this many samples (16 per half)
};

struct SteadyState {
  std::optional<double> steady_from;  // time of the first sample of the steady remainder
  std::string reason;                 // why not, when steady_from is empty
  bool too_short = false;             // too few samples to judge at all
  double trend_z = 0.0;               // the tests' statistics at steady_from (or at the last candidate)
  double halves_z = 0.0;
};

// time: increasing sample times; value: the series (e.g. timeseries.csv's kinetic_energy).
SteadyState detect_steady_state(std::span<const double> time, std::span<const double> value,
                                const SteadyStateOptions& options = {});

}  // namespace grainflow::analysis
