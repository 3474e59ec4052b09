// Steady one-dimensional kinetic theory of a vibrated bed: identical smooth inelastic spheres over a
// flat floor that vibrates along gravity, the theory Lan 1994 (section 4.1) compares its depth
// profiles W(Y) and nu(Y) with ("kinetic theory predictions of Richman and Martin"). The thesis has
// no curves and no equations for it, so the model here is assembled from the sources below and
// stated in full in docs/MODELS.md, "Kinetic theory of a vibrated bed".
//
// Everything is dimensionless: lengths in d, temperature theta = T/(g d) (T per degree of freedom,
// m^2/s^2), pressure P = p/(rho_s g d), heat flux Q = q/(rho_s (g d)^{3/2}). Y = y/d above the floor.
//
//   momentum   dP/dY = -nu,               P = nu theta F(nu),  F = 1 + 2(1+e) nu g0(nu)
//   energy     dQ/dY = -Gamma,            Q = -k(nu) sqrt(theta) dtheta/dY
//   Gamma = 12 (1-e^2) nu^2 g0 theta^{3/2} / sqrt(pi)                (Jenkins & Savage 1983, Lun et al. 1984)
//   k     = 75 sqrt(pi) / (48 eta (41-33 eta)) / g0 * [(1 + 12/5 eta nu g0)(1 + 12/5 eta^2 (4 eta-3) nu g0)
//           + 64/(25 pi) (41-33 eta) eta^2 (nu g0)^2],  eta = (1+e)/2   (Lun et al. 1984; Enskog at e = 1)
//   g0: Carnahan & Starling (2-nu)/(2(1-nu)^3) (Lan eq. 4-3-4), or Torquato's (1995) form, equal to it
//       below the freezing point 0.49 and diverging at random close packing 0.64.
//   Lun's density-gradient term of the heat flux (O(1-e)) is left out, as in the nearly elastic theory
//   of Jenkins & Richman (1985) that Richman & Martin (1992) use.
//
// Boundary conditions: P(0) = m_t (the floor carries the weight; with P -> 0 at the top this is the
// mass constraint, integral of nu dY = m_t); Q -> 0 at the top, where nu -> 0; and at the floor
// Q(0) = the energy the floor gives the bed, from a collision model: a Maxwellian at the floor's
// temperature hits a flat floor of normal restitution e_w whose velocity u along gravity is a
// sinusoid of random phase (the fast, small-amplitude vibration limit: the floor's displacement is
// neglected, its velocity is not), with the impact rate fixed by momentum balance (the mean force of
// the impacts equals the weight p(0)). See floor_exchange() and floor_heat_flux() below.
//
// Solved by shooting on the floor temperature theta(0): the ODEs are integrated upward (in
// t = ln(P(0)/P), so the dilute top becomes a finite interval) with an adaptive Dormand–Prince 5(4)
// method, and theta(0) is bisected until the heat flux reaching the top vanishes.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace grainflow::analysis {

// The radial distribution function at contact, g0(nu).
enum class ContactValueModel {
  carnahan_starling,  // (2-nu)/(2(1-nu)^3); finite up to nu = 1, so it lets a bed pack past 0.64
  torquato,           // Carnahan–Starling up to 0.49, then g0(0.49) (0.64-0.49)/(0.64-nu): nu < 0.64 always
};

inline constexpr double kFreezingFraction = 0.49;    // Torquato (1995): freezing point of hard spheres
inline constexpr double kRandomClosePacking = 0.64;  // Torquato (1995): random close packing

double contact_value(double nu, ContactValueModel model);
// F(nu) = p / (rho_s nu T) = 1 + 2 (1+e) nu g0.
double pressure_factor(double nu, double restitution, ContactValueModel model);
// k(nu) = kappa / (rho_s d sqrt(T)), the dimensionless conductivity above.
double conductivity_coefficient(double nu, double restitution, ContactValueModel model);
// Gamma / theta^{3/2} = 12 (1-e^2) nu^2 g0 / sqrt(pi).
double dissipation_coefficient(double nu, double restitution, ContactValueModel model);

// Impacts on the floor, per unit mass density of the impinging particles (m n_c) and averaged over
// the floor's phase: `energy` = <E>, the kinetic energy the bed gains per unit time and area;
// `momentum` = <M>, the momentum it hands to the floor. theta is the floor-side temperature, and
// floor_variance = <u^2>/(g d) the mean square of the floor's velocity along its normal (a sinusoid,
// u = sqrt(2 <u^2>) sin(phase)). Exact for a Maxwellian of temperature theta hitting a plane with
// velocity u: with s = sqrt(theta), a = u/s, Phi and phi the normal distribution and density,
//   <M> = (1+e_w) < s^2 ((a^2+1) Phi(a) + a phi(a)) >
//   <E> = < (1+e_w) u s^2 ((a^2+1) Phi(a) + a phi(a)) - (1-e_w^2)/2 s^3 ((a^3+3a) Phi(a) + (a^2+2) phi(a)) >.
// For <u^2> << theta: <E>/<M> = sqrt(theta/(2 pi)) [4 <u^2>/theta - 2 (1-e_w)] (1 + O(<u^2>/theta)).
struct FloorExchange {
  double energy = 0.0;
  double momentum = 0.0;
};
FloorExchange floor_exchange(double theta, double floor_variance, double floor_restitution);

// Q(0) = P(0) <E>/<M>: the impact rate chosen so the impacts' mean force carries the bed.
double floor_heat_flux(double pressure, double theta, double floor_variance, double floor_restitution);

struct KineticTheoryParameters {
  double restitution = 0.9;        // e, particle–particle, in [0, 1]
  double floor_restitution = 0.9;  // e_w, particle–floor, in [0, 1]
  double mass_holdup = 1.0;        // m_t = N pi d^2 / (6 A) = integral of nu dY (Lan eq. 4-1-3)
  double floor_variance = 1.0;     // <u^2>/(g d) of the floor's velocity along gravity, > 0;
                                   // V_b^2 for Lan's rotary drive (eq. 4-1-1), 3 V_b^2 for a vertical one
  ContactValueModel contact_value = ContactValueModel::torquato;
  double top_pressure_fraction = 1e-10;  // the profile ends where P = this * m_t (the mass left above is that)
  double output_spacing = 0.02;          // largest Delta Y between profile points, times max(1, theta)
};

// The floor's mean-square normal velocity <u^2>/(g d) for Lan's boundary fluctuation velocity V_b
// (eq. 4-1-3, V^2 = <|v|^2>/3): rotary drive (eq. 4-1-1), whose vertical component has <u^2> = V^2;
// vertical drive, <u^2> = <|v|^2> = 3 V^2.
inline double floor_variance_rotary(double vb) { return vb * vb; }
inline double floor_variance_vertical(double vb) { return 3.0 * vb * vb; }

struct KineticTheoryProfile {
  // One entry per point, from the floor (Y = 0) up to where P = top_pressure_fraction * m_t.
  std::vector<double> Y;                // y / d
  std::vector<double> solids_fraction;  // nu
  std::vector<double> W;                // sqrt(T/(g d)) (Lan eq. 4-1-4)
  std::vector<double> temperature;      // theta = T/(g d)
  std::vector<double> pressure;         // P = p/(rho_s g d)
  std::vector<double> heat_flux;        // Q = q/(rho_s (g d)^{3/2}), upward
  std::vector<double> dissipation;      // Gamma = gamma d/(rho_s (g d)^{3/2})
  double floor_heat_flux = 0.0;         // Q(0), from the floor model
  double top_heat_flux = 0.0;           // Q at the last point: the shooting residual
  int shooting_iterations = 0;
  std::vector<std::string> warnings;  // where the result is outside the theory's range
};

// Invalid parameters: std::invalid_argument. No steady solution found: KineticTheoryError.
class KineticTheoryError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

KineticTheoryProfile solve_vibrated_bed(const KineticTheoryParameters& parameters);

}  // namespace grainflow::analysis
