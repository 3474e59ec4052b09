#include "grainflow/analysis/constitutive_functions.hpp"

#include <cmath>
#include <limits>

namespace grainflow::analysis {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double squared(double x) { return x * x; }

// The error of value = a / (c b^power) from the errors of a and b (finite also where a = 0).
double ratio_error(double value, double a_error, double per_a, double b, double b_error, double power = 1.0) {
  return std::hypot(a_error * per_a, value * power * b_error / b);
}

}  // namespace

ConstitutiveValues constitutive_functions(const ConstitutiveInputs& m, double material_density, double radius) {
  ConstitutiveValues v;
  const double energy = material_density * m.velocity_variance;
  v.chi = energy > 0.0 ? m.normal_stress / energy : kNaN;
  v.chi_error = ratio_error(v.chi, m.normal_stress_error, 1.0 / energy, m.velocity_variance, m.velocity_variance_error);
  const double shear = material_density * squared(radius * m.du_dy);
  // The shear stress takes the sign of du/dy so that f_s > 0 whenever the stress resists the shear.
  v.f_s = shear > 0.0 ? std::copysign(1.0, m.du_dy) * m.shear_stress / shear : kNaN;
  v.f_n = shear > 0.0 ? m.normal_stress / shear : kNaN;
  v.f_s_error = ratio_error(v.f_s, m.shear_stress_error, 1.0 / shear, m.du_dy, m.du_dy_error, 2.0);
  v.f_n_error = ratio_error(v.f_n, m.normal_stress_error, 1.0 / shear, m.du_dy, m.du_dy_error, 2.0);
  return v;
}

double equivalent_3d_solids_fraction(double nu) { return 4.0 / (3.0 * std::sqrt(M_PI)) * std::pow(nu, 1.5); }

double elastic_gas_chi(double nu, int dimension) {
  if (dimension == 2) return nu * (1.0 + nu * nu / 8.0) / squared(1.0 - nu) / 2.0;  // Henderson
  return nu * (1.0 + nu + nu * nu - nu * nu * nu) / std::pow(1.0 - nu, 3) / 3.0;    // Carnahan-Starling
}

}  // namespace grainflow::analysis
