// Campbell's (1982) constitutive functions of a shear flow, strip by strip:
//  - the equation-of-state function chi(nu) of section 3.1.1, p = rho_p chi(nu) sum_i <u_i'^2>
//    (2D: <u'^2> + <v'^2>, Campbell's form; 3D: with <w'^2>, the same translational energy);
//  - the Bagnold/Savage functions of section 3.3.1, tau_s = rho_p f_s(nu) R^2 (du/dy)^2 and
//    tau_N = rho_p f_N(nu) R^2 (du/dy)^2;
//  - the 2D -> 3D solids-fraction correspondence of section 3.1, nu_3D = 4 / (3 sqrt pi) nu^(3/2),
//    from equal mean particle spacings;
//  - for reference, chi of an elastic hard-particle gas: p = n k T Z(nu) with n m = rho_p nu and
//    k T = m <u_i'^2> per component gives chi = nu Z(nu) / D, with Henderson's (1975) Z for discs
//    and Carnahan & Starling's (1969) for spheres (the equations of state the engine is tested on).
// rho_p is the particles' material density (mass per disc area in 2D, per sphere volume in 3D).
#pragma once

namespace grainflow::analysis {

// One strip's averages, each with its standard error.
struct ConstitutiveInputs {
  double solids_fraction = 0.0, solids_fraction_error = 0.0;
  double velocity_variance = 0.0, velocity_variance_error = 0.0;  // m^2/s^2, sum_i <u_i'^2>
  double normal_stress = 0.0, normal_stress_error = 0.0;          // tau_N = P_yy, compressive positive (Pa; 2D N/m)
  double shear_stress = 0.0, shear_stress_error = 0.0;            // tau_s = -P_yx: positive where it resists du/dy > 0
  double du_dy = 0.0, du_dy_error = 0.0;                          // 1/s
};

struct ConstitutiveValues {
  double chi = 0.0, chi_error = 0.0;
  double f_s = 0.0, f_s_error = 0.0;  // signed so that a stress resisting the shear counts positive
  double f_n = 0.0, f_n_error = 0.0;
};

// chi, f_s and f_N with errors propagated to first order from independent relative errors (the
// inputs' errors come from separate block averages; their correlation is ignored). NaN where a
// denominator vanishes.
ConstitutiveValues constitutive_functions(const ConstitutiveInputs& m, double material_density, double radius);

// Campbell's equivalent 3D solids fraction of a 2D one (section 3.1): pi/4 maps to pi/6.
double equivalent_3d_solids_fraction(double nu);

// chi of an elastic hard-particle gas at solids fraction nu: nu Z(nu) / D (D = 2 discs, 3 spheres).
double elastic_gas_chi(double nu, int dimension);

}  // namespace grainflow::analysis
