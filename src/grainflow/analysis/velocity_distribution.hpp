// Velocity distributions of Campbell 1982 section 3.4.1. Strip means first: each particle belongs
// to the strip holding its centre, and <q>, <q'^2> of every velocity component q (u, v, w and the
// spins) are taken per strip over all samples. Then each sample's particles give the sampled
// variables X = |q - <q>| / sqrt(<q'^2>) (single components) or, for combinations, the square root
// of the fluctuation energy over its strip mean (spins weighted by beta = I/m, Campbell's X5).
// Histograms on [0, x_max) are normalised by the total count and the bin width, so that
// integral_0^inf P dX = 1, and fitted by least squares with the generalized Maxwellian of k
// components, P_k(X) = 2 a^(k/2) / Gamma(k/2) X^(k-1) exp(-a X^2), whose Maxwellian value is
// a_m = k/2. (For k = 1 this is twice Campbell's sqrt(a/pi) exp(-a X^2), which is normalised on the
// whole line: X = |q - <q>| folds it onto [0, inf). k = 2, 3 are his P4 and P5 unchanged.)
#pragma once

#include <string>
#include <vector>

#include "grainflow/analysis/state_samples.hpp"

namespace grainflow::analysis {

// P_k(X), normalised on [0, inf); its second moment is k / (2a), so a = k/2 when <X^2> = 1.
double generalized_maxwellian(int components, double a, double x);

struct MaxwellFit {
  double a = 0.0;      // least-squares a
  double error = 0.0;  // its standard error from the residuals: sqrt(RSS / (bins - 1) / sum (dP/da)^2)
};

// Least-squares fit of P_k(X; a) to a histogram density: `density` over bins of width `bin_width`
// centred at `x`, each compared with P_k averaged over its bin.
MaxwellFit fit_generalized_maxwellian(int components, const std::vector<double>& x, double bin_width,
                                      const std::vector<double>& density);

// Velocity components: u, v, w (translation) and the spins omega_x, omega_y, omega_z.
enum Component { kU = 0, kV, kW, kSpinX, kSpinY, kSpinZ, kComponents };

struct SampledVariable {
  std::string name;             // "X1" ...
  std::string components_text;  // "u", "u,v,omega" ...
  std::vector<int> components;
  std::vector<double> density;  // per bin, 1/X
  long long beyond = 0;         // values at or above x_max (counted in the normalisation)
  MaxwellFit fit;
  double maxwell_a() const { return 0.5 * static_cast<double>(components.size()); }
};

// Campbell's X1..X5. 2D: u, v, omega, (u, v), (u, v, omega). 3D: u, v, omega_z (the spin about the
// vorticity axis, as in 2D), (u, v, w), all six components, and X6 = w.
std::vector<SampledVariable> campbell_variables(int dimension);

struct StripMoments {
  long long count = 0;                // particle samples whose centre lay in the strip
  double centre = 0.0;                // m, the strip's centre averaged over the samples
  double mean[kComponents] = {};      // <q>
  double variance[kComponents] = {};  // <(q - <q>)^2>
  double energy[kComponents] = {};    // <weight (q - <q>)^2>: weight 1, beta for spins (m^2/s^2)
};

struct VelocityDistributionOptions {
  int first_strip = 0, last_strip = -1;  // the strips counted (inclusive); -1: the last
  int bins = 50;
  double x_max = 5.0;
};

struct VelocityDistributions {
  std::vector<double> x;  // bin centres
  double bin_width = 0.0;
  std::vector<SampledVariable> variables;
  std::vector<StripMoments> strips;
  int first_strip = 0, last_strip = 0;
  long long counted = 0;      // particle samples in the selected strips
  double diameter = 0.0;      // m, mean over the particles
  double shear_rate = 0.0;    // 1/s, du/dy: least squares over the middle half of the selected strips
  double u2 = 0.0, v2 = 0.0;  // m^2/s^2, <u'^2>, <v'^2> over the selected strips
  double s_u = 0.0;           // 2R du/dy / sqrt(<u'^2>)
  double s_uv = 0.0;          // 2R du/dy / sqrt(<u'^2> + <v'^2>)
};

VelocityDistributions velocity_distributions(const StateSamples& s, const VelocityDistributionOptions& options);

}  // namespace grainflow::analysis
