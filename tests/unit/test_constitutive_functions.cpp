// Campbell's constitutive functions (analysis/constitutive_functions.hpp): the algebra of chi, f_s
// and f_N with their propagated errors, the 2D -> 3D solids-fraction correspondence at the packings
// where it is exact, and the elastic-gas chi's limits. Every expected value is worked out by hand
// in the comment beside it; the tolerances are round-off.
#include <gtest/gtest.h>

#include <cmath>

#include "grainflow/analysis/constitutive_functions.hpp"

using namespace grainflow::analysis;

TEST(ConstitutiveFunctions, ChiAndBagnoldFunctionsFromTheirDefinitions) {
  ConstitutiveInputs m;
  m.solids_fraction = 0.5;
  m.velocity_variance = 2.0, m.velocity_variance_error = 0.2;  // 10 %
  m.normal_stress = 3.0, m.normal_stress_error = 0.3;          // 10 %
  m.shear_stress = 1.5, m.shear_stress_error = 0.0;
  m.du_dy = 0.5, m.du_dy_error = 0.05;  // 10 %
  const double rho = 0.25, radius = 2.0;
  const auto v = constitutive_functions(m, rho, radius);
  EXPECT_NEAR(v.chi, 3.0 / (0.25 * 2.0), 1e-15);                   // 6
  EXPECT_NEAR(v.chi_error, 6.0 * std::sqrt(0.01 + 0.01), 1e-14);   // two 10 % errors in quadrature
  const double shear = rho * radius * radius * 0.25;               // rho R^2 (du/dy)^2 = 0.25
  EXPECT_NEAR(v.f_n, 3.0 / shear, 1e-14);                          // 12
  EXPECT_NEAR(v.f_s, 1.5 / shear, 1e-14);                          // 6
  EXPECT_NEAR(v.f_n_error, 12.0 * std::sqrt(0.01 + 0.04), 1e-13);  // (du/dy)^2 doubles its 10 %
  EXPECT_NEAR(v.f_s_error, 6.0 * 0.2, 1e-13);
}

TEST(ConstitutiveFunctions, ShearFunctionIsPositiveWhenTheStressResistsTheShear) {
  // A flow sheared the other way (du/dy < 0) resists with tau_s = -P_yx < 0: f_s stays positive.
  ConstitutiveInputs m;
  m.velocity_variance = 1.0, m.normal_stress = 1.0;
  m.shear_stress = -0.4, m.du_dy = -2.0;
  const auto v = constitutive_functions(m, 1.0, 1.0);
  EXPECT_NEAR(v.f_s, 0.1, 1e-15);   // 0.4 / 4
  EXPECT_NEAR(v.f_n, 0.25, 1e-15);  // 1 / 4
}

TEST(ConstitutiveFunctions, UndefinedWithoutShearOrFluctuations) {
  ConstitutiveInputs m;  // a plug at rest: no variance, no gradient
  m.normal_stress = 1.0;
  const auto v = constitutive_functions(m, 1.0, 1.0);
  EXPECT_TRUE(std::isnan(v.chi));
  EXPECT_TRUE(std::isnan(v.f_s));
  EXPECT_TRUE(std::isnan(v.f_n));
}

TEST(ConstitutiveFunctions, ZeroStressHasAFiniteError) {
  // A strip whose shear stress averages to zero still has the stress's own error in f_s.
  ConstitutiveInputs m;
  m.velocity_variance = 1.0, m.normal_stress = 1.0;
  m.shear_stress = 0.0, m.shear_stress_error = 0.1, m.du_dy = 1.0, m.du_dy_error = 0.1;
  const auto v = constitutive_functions(m, 1.0, 1.0);
  EXPECT_EQ(v.f_s, 0.0);
  EXPECT_NEAR(v.f_s_error, 0.1, 1e-15);
}

TEST(ConstitutiveFunctions, EquivalentSolidsFractionMapsSquareToCubicPacking) {
  // Equal spacings C: a square lattice of discs (pi/4) corresponds to a simple cubic one of spheres
  // (pi/6): nu_3D = 4/(3 sqrt pi) nu^(3/2) sends pi/4 to 4/(3 sqrt pi) pi^(3/2)/8 = pi/6 exactly.
  EXPECT_NEAR(equivalent_3d_solids_fraction(M_PI / 4.0), M_PI / 6.0, 1e-15);
  EXPECT_EQ(equivalent_3d_solids_fraction(0.0), 0.0);
  // Scaling: nu -> 4 nu multiplies nu_3D by 8.
  EXPECT_NEAR(equivalent_3d_solids_fraction(0.2) / equivalent_3d_solids_fraction(0.05), 8.0, 1e-13);
}

TEST(ConstitutiveFunctions, ElasticGasChiHasTheIdealGasLimitAndTheEquationsOfState) {
  // Dilute: chi -> nu / D (p = n k T, rho_p nu = n m, k T = m <u'^2> per component), with the
  // second virial coefficient Z = 1 + 2 nu (discs), 1 + 4 nu (spheres); the rest is O(nu^2) = 1e-12.
  const double nu = 1e-6;
  EXPECT_NEAR(elastic_gas_chi(nu, 2) / nu, (1.0 + 2.0 * nu) / 2.0, 1e-11);
  EXPECT_NEAR(elastic_gas_chi(nu, 3) / nu, (1.0 + 4.0 * nu) / 3.0, 1e-11);
  // Henderson at nu = 0.5: Z = (1 + 1/32) / 0.25 = 4.125, chi = 0.5 x 4.125 / 2.
  EXPECT_NEAR(elastic_gas_chi(0.5, 2), 1.03125, 1e-14);
  // Carnahan-Starling at nu = 0.3: Z = (1 + 0.3 + 0.09 - 0.027) / 0.343 = 3.97376..., chi = 0.1 Z.
  EXPECT_NEAR(elastic_gas_chi(0.3, 3), 0.1 * 1.363 / 0.343, 1e-14);
}
