#include "grainflow/analysis/kinetic_theory.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

namespace grainflow::analysis {

namespace {

constexpr double kPi = 3.14159265358979323846;

// dg0/dnu.
double contact_value_slope(double nu, ContactValueModel model) {
  if (model == ContactValueModel::torquato && nu > kFreezingFraction)
    return contact_value(nu, model) / (kRandomClosePacking - nu);
  return (5.0 - 2.0 * nu) / (2.0 * std::pow(1.0 - nu, 4));
}

}  // namespace

double contact_value(double nu, ContactValueModel model) {
  if (model == ContactValueModel::torquato && nu > kFreezingFraction) {
    const double at_freezing = (2.0 - kFreezingFraction) / (2.0 * std::pow(1.0 - kFreezingFraction, 3));
    return at_freezing * (kRandomClosePacking - kFreezingFraction) / (kRandomClosePacking - nu);
  }
  return (2.0 - nu) / (2.0 * std::pow(1.0 - nu, 3));
}

double pressure_factor(double nu, double restitution, ContactValueModel model) {
  return 1.0 + 2.0 * (1.0 + restitution) * nu * contact_value(nu, model);
}

double conductivity_coefficient(double nu, double restitution, ContactValueModel model) {
  const double eta = 0.5 * (1.0 + restitution);
  const double g0 = contact_value(nu, model), x = nu * g0;
  const double dilute = 75.0 * std::sqrt(kPi) / (48.0 * eta * (41.0 - 33.0 * eta));
  return dilute / g0 *
         ((1.0 + 2.4 * eta * x) * (1.0 + 2.4 * eta * eta * (4.0 * eta - 3.0) * x) +
          64.0 / (25.0 * kPi) * (41.0 - 33.0 * eta) * eta * eta * x * x);
}

double dissipation_coefficient(double nu, double restitution, ContactValueModel model) {
  return 12.0 * (1.0 - restitution * restitution) * nu * nu * contact_value(nu, model) / std::sqrt(kPi);
}

FloorExchange floor_exchange(double theta, double floor_variance, double floor_restitution) {
  const double s = std::sqrt(theta), amplitude = std::sqrt(2.0 * floor_variance), ew = floor_restitution;
  // The integrand is a smooth periodic function of the phase, so the trapezoid rule over one period
  // converges geometrically; 256 points leave errors at round-off for amplitude / s up to ~30, and
  // beyond that the floor model is far outside its assumptions anyway.
  constexpr int kPhases = 256;
  FloorExchange sum;
  for (int k = 0; k < kPhases; ++k) {
    const double u = amplitude * std::sin(2.0 * kPi * (k + 0.5) / kPhases);
    const double a = u / s;
    const double Phi = 0.5 * std::erfc(-a / std::sqrt(2.0));
    const double phi = std::exp(-0.5 * a * a) / std::sqrt(2.0 * kPi);
    // I_k = integral over approaching particles of n(v)/n_c |v - u|^k, in closed form.
    const double i2 = theta * ((a * a + 1.0) * Phi + a * phi);
    const double i3 = theta * s * ((a * a * a + 3.0 * a) * Phi + (a * a + 2.0) * phi);
    sum.momentum += (1.0 + ew) * i2;
    sum.energy += (1.0 + ew) * u * i2 - 0.5 * (1.0 - ew * ew) * i3;
  }
  sum.momentum /= kPhases;
  sum.energy /= kPhases;
  return sum;
}

double floor_heat_flux(double pressure, double theta, double floor_variance, double floor_restitution) {
  const FloorExchange x = floor_exchange(theta, floor_variance, floor_restitution);
  return pressure * x.energy / x.momentum;
}

namespace {

struct Model {
  double e, ew, mt, u2;
  ContactValueModel cv;
  double nu_limit() const { return cv == ContactValueModel::torquato ? kRandomClosePacking : 1.0; }

  // G(nu) = nu F(nu) = P / theta; increasing from 0 to infinity on [0, nu_limit).
  double g(double nu) const { return nu * pressure_factor(nu, e, cv); }
  double g_slope(double nu) const {
    const double g0 = contact_value(nu, cv);
    return 1.0 + 2.0 * (1.0 + e) * (2.0 * nu * g0 + nu * nu * contact_value_slope(nu, cv));
  }

  // The solids fraction with nu F(nu) = ratio. Torquato's dense branch has g0 = A/(0.64 - nu), so
  // there nu solves (B-1) nu^2 + (0.64 + ratio) nu - 0.64 ratio = 0 with B = 2(1+e)A (> 1), taken in
  // the form without cancellation. Elsewhere: Newton on ln G (good both where G ~ nu and near the
  // pole of the Carnahan–Starling g0 at 1), kept inside a shrinking bracket.
  double solids_fraction(double ratio) const {
    if (!(ratio > 0.0)) return 0.0;
    double hi = 1.0;
    if (cv == ContactValueModel::torquato) {
      if (ratio >= g(kFreezingFraction)) {
        const double A = contact_value(kFreezingFraction, cv) * (kRandomClosePacking - kFreezingFraction);
        const double B = 2.0 * (1.0 + e) * A, b = kRandomClosePacking + ratio;
        return 2.0 * ratio * kRandomClosePacking /
               (b + std::sqrt(b * b + 4.0 * (B - 1.0) * ratio * kRandomClosePacking));
      }
      hi = kFreezingFraction;
    }
    double lo = 0.0, nu = std::min(ratio, 0.5 * hi);
    const double target = std::log(ratio);
    for (int it = 0; it < 100; ++it) {
      const double gv = g(nu);
      const double h = std::log(gv) - target;
      if (h > 0.0) hi = nu;
      else lo = nu;
      double next = nu - h * gv / g_slope(nu);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (std::fabs(next - nu) <= 1e-15 * nu) return next;
      nu = next;
    }
    return nu;
  }
};

// The ODEs in t = ln(P(0)/P): state (Y, theta, Q); with P/nu = dY/dt,
//   dY/dt = P/nu,  dtheta/dt = -Q/(k sqrt(theta)) P/nu,  dQ/dt = -Gamma P/nu.
using State = std::array<double, 3>;

struct Point {
  double Y, theta, Q, nu, P;
};

struct Shot {
  bool crashed = false;  // theta fell to zero below the top: too much heat from the floor
  double floor_flux = 0.0;
  double top_flux = 0.0;
  std::vector<Point> points;
};

class Integrator {
 public:
  Integrator(const Model& m, const KineticTheoryParameters& p) : m_(m), p_(p) {}

  // Evaluates the right-hand side; false where it is undefined (theta <= 0).
  bool rhs(double t, const State& y, State& dy, double* nu_out = nullptr) const {
    const double theta = y[1];
    if (!(theta > 0.0) || !std::isfinite(theta)) return false;
    const double P = m_.mt * std::exp(-t);
    const double nu = m_.solids_fraction(P / theta);
    if (!(nu > 0.0)) return false;
    const double rate = P / nu;
    dy[0] = rate;
    dy[1] = -y[2] / (conductivity_coefficient(nu, m_.e, m_.cv) * std::sqrt(theta)) * rate;
    dy[2] = -dissipation_coefficient(nu, m_.e, m_.cv) * theta * std::sqrt(theta) * rate;
    if (nu_out) *nu_out = nu;
    return true;
  }

  Shot shoot(double theta0, bool record) const {
    Shot shot;
    const double t_end = std::log(1.0 / p_.top_pressure_fraction);
    shot.floor_flux = floor_heat_flux(m_.mt, theta0, m_.u2, m_.ew);
    State y{0.0, theta0, shot.floor_flux};
    double t = 0.0, h = 1e-3, nu = 0.0;
    State k1;
    if (!rhs(t, y, k1, &nu)) throw KineticTheoryError("kinetic theory: undefined state at the floor");
    if (record) shot.points.push_back({0.0, theta0, y[2], nu, m_.mt});
    constexpr double rtol = 1e-10;
    for (long step = 0;; ++step) {
      if (step > 2000000) throw KineticTheoryError("kinetic theory: the integration took more than 2e6 steps");
      // Keep Delta Y below output_spacing * max(1, theta), so the recorded points resolve the profile.
      const double cap = p_.output_spacing * std::max(1.0, y[1]) / k1[0];
      h = std::min(h, cap);
      if (h < 1e-13 * std::max(1.0, t)) {  // cannot step on: theta is collapsing to zero
        shot.crashed = true;
        return shot;
      }
      h = std::min(h, t_end - t);
      State y5, err;
      std::array<State, 7> k;
      k[0] = k1;
      bool ok = true;
      for (int stage = 1; stage < 7 && ok; ++stage) {
        State ys = y;
        for (int i = 0; i < 3; ++i) {
          double sum = 0.0;
          for (int j = 0; j < stage; ++j) sum += kA[stage][j] * k[j][i];
          ys[i] += h * sum;
        }
        ok = rhs(t + kC[stage] * h, ys, k[stage]);
        if (stage == 6) y5 = ys;  // the 7th stage is evaluated at the 5th-order solution (FSAL)
      }
      double norm = std::numeric_limits<double>::infinity();
      if (ok) {
        norm = 0.0;
        // Error scales: Y and theta relative; Q relative to the flux scale P(0) sqrt(theta).
        const double scale[3] = {rtol * std::max({1.0, std::fabs(y[0]), std::fabs(y5[0])}),
                                 rtol * std::max(std::fabs(y[1]), std::fabs(y5[1])),
                                 rtol * std::max({std::fabs(y[2]), std::fabs(y5[2]), 1e-3 * m_.mt * std::sqrt(y[1])})};
        for (int i = 0; i < 3; ++i) {
          double e = 0.0;
          for (int j = 0; j < 7; ++j) e += kE[j] * k[j][i];
          err[i] = h * e;
          norm = std::max(norm, std::fabs(err[i]) / scale[i]);
        }
      }
      if (!(norm <= 1.0)) {
        h *= ok ? std::clamp(0.9 * std::pow(norm, -0.2), 0.1, 0.5) : 0.25;
        continue;
      }
      t += h;
      y = y5;
      k1 = k[6];
      if (!rhs(t, y, k1, &nu)) {  // cannot happen after an accepted step, but be safe
        shot.crashed = true;
        return shot;
      }
      if (record) shot.points.push_back({y[0], y[1], y[2], nu, m_.mt * std::exp(-t)});
      // theta collapsing with heat still flowing up: it would reach zero below the top. (A true
      // solution falls this low only in a dense bed some 35 d deep, beyond what shooting can follow.)
      if (y[1] < 1e-12 * theta0 && y[2] > 0.0) {
        shot.crashed = true;
        return shot;
      }
      if (t >= t_end * (1.0 - 1e-15)) break;
      h *= std::clamp(0.9 * std::pow(std::max(norm, 1e-10), -0.2), 0.2, 5.0);
    }
    shot.top_flux = y[2];
    return shot;
  }

 private:
  // Dormand & Prince (1980) RK5(4)7M.
  static constexpr double kC[7] = {0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
  static constexpr double kA[7][6] = {
      {},
      {1.0 / 5},
      {3.0 / 40, 9.0 / 40},
      {44.0 / 45, -56.0 / 15, 32.0 / 9},
      {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
      {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
      {35.0 / 384, 0.0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84},
  };
  // 5th-order weights minus the embedded 4th-order ones.
  static constexpr double kE[7] = {35.0 / 384 - 5179.0 / 57600,
                                   0.0,
                                   500.0 / 1113 - 7571.0 / 16695,
                                   125.0 / 192 - 393.0 / 640,
                                   -2187.0 / 6784 + 92097.0 / 339200,
                                   11.0 / 84 - 187.0 / 2100,
                                   -1.0 / 40};

  const Model& m_;
  const KineticTheoryParameters& p_;
};

void validate(const KineticTheoryParameters& p) {
  auto fail = [](const std::string& what) { throw std::invalid_argument("kinetic theory: " + what); };
  if (!(p.restitution >= 0.0 && p.restitution <= 1.0)) fail("restitution e must lie in [0, 1]");
  if (!(p.floor_restitution >= 0.0 && p.floor_restitution <= 1.0)) fail("floor restitution e_w must lie in [0, 1]");
  if (!(p.mass_holdup > 0.0) || !std::isfinite(p.mass_holdup)) fail("mass hold-up m_t must be positive");
  if (!(p.floor_variance > 0.0) || !std::isfinite(p.floor_variance))
    fail("the floor's mean-square velocity must be positive: a still floor gives the bed no energy");
  if (p.restitution == 1.0 && p.floor_restitution == 1.0)
    fail("with e = e_w = 1 nothing dissipates the energy the floor brings: there is no steady state");
  if (!(p.top_pressure_fraction > 0.0 && p.top_pressure_fraction < 1e-3))
    fail("top_pressure_fraction must lie in (0, 1e-3)");
  if (!(p.output_spacing > 0.0 && p.output_spacing <= 1.0)) fail("output_spacing must lie in (0, 1]");
}

std::string format(double x) {
  std::ostringstream s;
  s.precision(4);
  s << x;
  return s.str();
}

}  // namespace

KineticTheoryProfile solve_vibrated_bed(const KineticTheoryParameters& parameters) {
  validate(parameters);
  const Model model{parameters.restitution, parameters.floor_restitution, parameters.mass_holdup,
                    parameters.floor_variance, parameters.contact_value};
  const Integrator integrator(model, parameters);

  // Residual sign: +1 when theta(0) is too low (heat left at the top, or theta collapsing to zero
  // on the way up), -1 when too high (the bed dissipates more than the floor gives). A colder floor
  // gives more energy and conducts less, so the sign is + at low theta(0) and - at high; bisection
  // needs only a bracket, and the result is checked against the top condition below.
  auto sign = [&](double x, int& count) {
    ++count;
    const Shot s = integrator.shoot(std::exp(x), false);
    return s.crashed || s.top_flux > 0.0 ? 1 : -1;
  };
  int count = 0;
  const double x_min = std::log(1e-12), x_max = std::log(1e12), widen = std::log(4.0);
  const double x0 = std::log(std::max(parameters.floor_variance, 1e-10));
  double x_lo = x0, x_hi = x0;
  if (sign(x0, count) > 0) {
    do {
      x_lo = x_hi;
      x_hi += widen;
      if (x_hi > x_max)
        throw KineticTheoryError(
            "kinetic theory: no floor temperature below 1e12 g d balances the floor's energy input");
    } while (sign(x_hi, count) > 0);
  } else {
    do {
      x_hi = x_lo;
      x_lo -= widen;
      if (x_lo < x_min)
        throw KineticTheoryError("kinetic theory: no floor temperature above 1e-12 g d balances the bed's dissipation");
    } while (sign(x_lo, count) < 0);
  }
  while (x_hi - x_lo > 1e-14 * std::max(1.0, std::fabs(x_hi))) {
    const double mid = 0.5 * (x_lo + x_hi);
    if (mid <= x_lo || mid >= x_hi) break;
    (sign(mid, count) > 0 ? x_lo : x_hi) = mid;
  }

  const double theta0 = std::exp(x_hi);
  const Shot shot = integrator.shoot(theta0, true);
  const double flux_scale = std::max(std::fabs(shot.floor_flux), parameters.mass_holdup * std::sqrt(theta0));
  if (shot.crashed || std::fabs(shot.top_flux) > 1e-6 * flux_scale)
    throw KineticTheoryError(
        "kinetic theory: shooting on the floor temperature cannot meet the zero-flux condition at the top (heat flux "
        "left there " +
        format(shot.top_flux) + " against " + format(flux_scale) +
        " at the floor, with theta(0) "
        "resolved to round-off): the bed is too deep and dense for the temperature to be followed through it");

  KineticTheoryProfile out;
  out.floor_heat_flux = shot.floor_flux;
  out.top_heat_flux = shot.top_flux;
  out.shooting_iterations = count;
  double nu_max = 0.0, y_max = 0.0;
  for (const Point& p : shot.points) {
    out.Y.push_back(p.Y);
    out.solids_fraction.push_back(p.nu);
    out.W.push_back(std::sqrt(p.theta));
    out.temperature.push_back(p.theta);
    out.pressure.push_back(p.P);
    out.heat_flux.push_back(p.Q);
    out.dissipation.push_back(dissipation_coefficient(p.nu, model.e, model.cv) * p.theta * std::sqrt(p.theta));
    if (p.nu > nu_max) {
      nu_max = p.nu;
      y_max = p.Y;
    }
  }
  if (model.cv == ContactValueModel::carnahan_starling && nu_max > kRandomClosePacking)
    throw KineticTheoryError("kinetic theory: the bed packs to nu = " + format(nu_max) + " at Y = " + format(y_max) +
                             ", beyond random close packing (0.64), with the Carnahan–Starling g0: it is not "
                             "fluidised; use the Torquato contact value to see the (jammed) profile");
  if (nu_max > 0.6)
    out.warnings.push_back("the solids fraction reaches " + format(nu_max) + " at Y = " + format(y_max) +
                           ", close to random close packing: the bed is barely fluidised there and kinetic theory is "
                           "outside its range (Lan 1994 section 4.1.4: the theory fails at low shaking acceleration)");
  const double floor_ratio = parameters.floor_variance / theta0;
  if (floor_ratio > 4.0)
    out.warnings.push_back("the floor's mean-square velocity is " + format(floor_ratio) +
                           " times the bed's temperature there: far from the nearly-Maxwellian impacts the floor "
                           "model assumes");
  return out;
}

}  // namespace grainflow::analysis
