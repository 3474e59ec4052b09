// Self-diffusion coefficients: from the integral of the velocity autocorrelation (Lan 1994
// eqs. 3-2-5, 4-4-1, 4-4-2), from the limiting slope of the mean-square displacement (the Einstein
// relation, eqs. 3-3-4, 3-3-5, 4-4-5, 4-4-6), and Savage's kinetic-theory value (eqs. 4-3-3, 4-3-4).
//
// Conventions (checked against the thesis): per component, D_x = integral_0^inf <v_x(t) v_x(0)> dt
// and MSD_x(t) -> 2 D_x t; the total is the mean of the components, D = (D_x + D_y + D_z) / 3
// (eq. 4-4-2; eq. 3-2-5 has the 1/3, eq. 3-3-5 the 1/(6t), although the text of section 3.2 calls D
// "the trace of the diffusion tensor": it is a third of the trace).
//
// Savage-Dai (1991), eq. (4-3-3): D = d sqrt(pi T) / (8 (1 + e) nu g0(nu)), with the
// Carnahan-Starling g0 = (2 - nu) / (2 (1 - nu)^3) (eq. 4-3-4). T is the cell-average granular
// temperature in m^2/s^2, T = <C^2>/3 (section 1.2.2: the mean over components, not their sum), nu
// the bulk solids fraction, d and e those of Table 4.4 (d = 0.1 m, e = 0.9). Exactly as written,
// with the table's own T and nu, it reproduces Table 4.5's analytic column: T = 0.7950, nu = 0.44
// -> 0.0053202 m^2/s (printed 0.00532); T = 13.80, nu = 0.14 -> 0.21162 m^2/s (printed 0.2116).
// No conversion of T is needed; reading the printed T as a trace (dividing it by 3) would give
// values sqrt(3) too small. Section 4.4 cites this formula as "(4-4-3)"; it is printed as (4-3-3).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace grainflow::analysis {

struct VacfIntegral {
  std::vector<double> running_integral;  // m^2/s, I(k) = trapezoid integral of the VACF over [0, k dt]
  double coefficient = 0.0;              // m^2/s, I at the last lag: D of this component
};

// D of one component from its velocity autocorrelation C(k) = <v(t + k dt) v(t)> (m^2/s^2,
// k = 0 .. K, e.g. from autocorrelation()) by the trapezoid rule. The running integral shows whether
// it has reached its plateau before K; if C has not decayed by K, the coefficient is truncated.
VacfIntegral diffusion_from_vacf(std::span<const double> vacf, double sample_interval);

struct MsdFit {
  double coefficient = 0.0;                 // m^2/s, slope / (2 dimensions)
  double slope = 0.0;                       // m^2/s, least-squares slope of MSD against t over the window
  double intercept = 0.0;                   // m^2, at t = 0
  std::size_t first_lag = 0, last_lag = 0;  // the window, inclusive
};

// D from the limiting slope of a mean-square displacement MSD(k) (m^2, k = 0 .. K, e.g. from
// mean_square_displacement()): an unweighted least-squares line through (k dt, MSD(k)) for
// first_lag <= k <= last_lag, and D = slope / (2 dimensions). dimensions = 1 for one component
// (eqs. 4-4-5, 4-4-6), 3 for the sum of three components (|r|^2, eq. 3-3-5). The window must
// start after the ballistic regime (t >> the velocity correlation time).
MsdFit diffusion_from_msd(std::span<const double> msd, double sample_interval, std::size_t first_lag,
                          std::size_t last_lag, int dimensions = 1);
// The same over the second half of the lags, K/2 .. K.
MsdFit diffusion_from_msd(std::span<const double> msd, double sample_interval, int dimensions = 1);

// The total D of eq. (4-4-2): the mean of the per-component coefficients.
double total_diffusion(std::span<const double> component_coefficients);

// Carnahan-Starling radial distribution at contact, eq. (4-3-4); 0 <= solids_fraction < 1.
double carnahan_starling_g0(double solids_fraction);

// Savage-Dai kinetic-theory self-diffusion coefficient (m^2/s), eq. (4-3-3); see the header note.
// diameter in m, temperature in m^2/s^2 (granular, per component, averaged over components),
// restitution in (-1, 1], 0 < solids_fraction < 1.
double savage_dai_diffusion(double diameter, double temperature, double restitution, double solids_fraction);

}  // namespace grainflow::analysis
