#include "grainflow/analysis/velocity_distribution.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/analysis/strip_grid.hpp"
#include "grainflow/analysis/least_squares_line.hpp"

namespace grainflow::analysis {
namespace {

// P_k averaged over the bin [x - w/2, x + w/2] (Simpson, 16 intervals: exact to ~1e-9 for bins of
// 0.1), what a histogram measures; evaluating P at bin centres instead biases a by ~0.1-0.2 %.
template <class F>
double bin_average(F f, double x, double w) {
  constexpr int kIntervals = 16;
  const double a = std::max(0.0, x - 0.5 * w), b = x + 0.5 * w, h = (b - a) / kIntervals;
  double sum = f(a) + f(b);
  for (int i = 1; i < kIntervals; ++i) sum += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
  return sum * h / 3.0 / w;
}

double residual_sum(int k, double a, const std::vector<double>& x, double w, const std::vector<double>& density) {
  double sum = 0.0;
  for (std::size_t b = 0; b < x.size(); ++b) {
    const double r = density[b] - bin_average([&](double t) { return generalized_maxwellian(k, a, t); }, x[b], w);
    sum += r * r;
  }
  return sum;
}

// The strip holding each particle sample's centre, -1 outside the strips.
std::vector<int> strip_of_each(const StateSamples& s) {
  std::vector<int> strip(s.samples * s.particles, -1);
  for (std::size_t t = 0; t < s.samples; ++t) {
    const observe::StripGrid grid(s.dimension, 1, s.strip_lo[t], s.strip_hi[t], s.strip_count, 1.0);
    for (std::size_t i = 0; i < s.particles; ++i) {
      double y = s.at(s.position, t, i)[1];
      if (s.period_y > 0.0) y = s.strip_lo[t] + y - s.period_y * std::floor((y - s.strip_lo[t]) / s.period_y);
      strip[t * s.particles + i] = grid.strip_of(y);
    }
  }
  return strip;
}

// q = (u, v, w, omega_x, omega_y, omega_z) of one particle sample.
void components_of(const StateSamples& s, std::size_t t, std::size_t i, double q[kComponents]) {
  const double* v = s.at(s.velocity, t, i);
  const double* w = s.at(s.angular_velocity, t, i);
  for (int a = 0; a < 3; ++a) {
    q[a] = v[a];
    q[3 + a] = w[a];
  }
}

// Least-squares slope of the strip means of u against the strip centres.
double fitted_slope(const std::vector<StripMoments>& strips, int first, int last) {
  std::vector<double> y, u, used;  // strips without particles weigh nothing
  for (int k = first; k <= last; ++k) {
    y.push_back(strips[k].centre);
    u.push_back(strips[k].count == 0 ? 0.0 : strips[k].mean[kU]);
    used.push_back(strips[k].count == 0 ? 0.0 : 1.0);
  }
  return fit_least_squares_line(y, u, used).slope;
}

}  // namespace

double generalized_maxwellian(int k, double a, double x) {
  if (x < 0.0 || !(a > 0.0)) return 0.0;
  const double half = 0.5 * k;
  return 2.0 * std::pow(a, half) / std::tgamma(half) * std::pow(x, k - 1) * std::exp(-a * x * x);
}

MaxwellFit fit_generalized_maxwellian(int k, const std::vector<double>& x, double w,
                                      const std::vector<double>& density) {
  MaxwellFit fit;
  if (x.size() < 2) return fit;
  // The residual sum is smooth in log a: scan a wide bracket around the Maxwellian value k/2, then
  // close in on the best point by golden sections.
  const double centre = std::log(0.5 * k), span = std::log(100.0);
  constexpr int kScan = 200;
  auto log_a = [&](int i) { return centre + span * (2.0 * i / kScan - 1.0); };
  int best = 0;
  double best_rss = residual_sum(k, std::exp(log_a(0)), x, w, density);
  for (int i = 1; i <= kScan; ++i)
    if (const double r = residual_sum(k, std::exp(log_a(i)), x, w, density); r < best_rss) {
      best_rss = r;
      best = i;
    }
  double lo = log_a(std::max(0, best - 1)), hi = log_a(std::min(kScan, best + 1));
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = hi - g * (hi - lo), d = lo + g * (hi - lo);
  double fc = residual_sum(k, std::exp(c), x, w, density), fd = residual_sum(k, std::exp(d), x, w, density);
  while (hi - lo > 1e-12) {
    if (fc < fd) {
      hi = d, d = c, fd = fc;
      c = hi - g * (hi - lo);
      fc = residual_sum(k, std::exp(c), x, w, density);
    } else {
      lo = c, c = d, fc = fd;
      d = lo + g * (hi - lo);
      fd = residual_sum(k, std::exp(d), x, w, density);
    }
  }
  fit.a = std::exp(0.5 * (lo + hi));
  // Linearised error: dP/da = P (k / (2a) - x^2); residual variance with one fitted parameter.
  double jacobian = 0.0;
  for (double xb : x) {
    const double derivative =
        bin_average([&](double t) { return generalized_maxwellian(k, fit.a, t) * (0.5 * k / fit.a - t * t); }, xb, w);
    jacobian += derivative * derivative;
  }
  const double rss = residual_sum(k, fit.a, x, w, density);
  fit.error = jacobian > 0.0 ? std::sqrt(rss / static_cast<double>(x.size() - 1) / jacobian) : 0.0;
  return fit;
}

std::vector<SampledVariable> campbell_variables(int dimension) {
  auto variable = [](std::string name, std::string text, std::vector<int> components) {
    SampledVariable v;
    v.name = std::move(name);
    v.components_text = std::move(text);
    v.components = std::move(components);
    return v;
  };
  if (dimension == 2)
    return {variable("X1", "u", {kU}), variable("X2", "v", {kV}), variable("X3", "omega", {kSpinZ}),
            variable("X4", "u,v", {kU, kV}), variable("X5", "u,v,omega", {kU, kV, kSpinZ})};
  return {variable("X1", "u", {kU}),
          variable("X2", "v", {kV}),
          variable("X3", "omega_z", {kSpinZ}),
          variable("X4", "u,v,w", {kU, kV, kW}),
          variable("X5", "u,v,w,omega_x,omega_y,omega_z", {kU, kV, kW, kSpinX, kSpinY, kSpinZ}),
          variable("X6", "w", {kW})};
}

VelocityDistributions velocity_distributions(const StateSamples& s, const VelocityDistributionOptions& o) {
  VelocityDistributions out;
  const int strips = std::max(1, s.strip_count);
  out.first_strip = std::clamp(o.first_strip, 0, strips - 1);
  out.last_strip = o.last_strip < 0 ? strips - 1 : std::clamp(o.last_strip, out.first_strip, strips - 1);
  out.diameter = 2.0 * s.mean_radius();
  out.bin_width = o.x_max / o.bins;
  for (int b = 0; b < o.bins; ++b) out.x.push_back((b + 0.5) * out.bin_width);
  out.variables = campbell_variables(s.dimension);
  out.strips.assign(strips, StripMoments{});
  const std::vector<int> strip = strip_of_each(s);
  auto weight = [&](std::size_t i, int c) { return c >= kSpinX ? s.inertia_factor * s.radius[i] * s.radius[i] : 1.0; };

  // visit(i, moments of i's strip, i's components) for every particle sample lying in a strip.
  auto for_each_in_strips = [&](auto&& visit) {
    for (std::size_t t = 0; t < s.samples; ++t)
      for (std::size_t i = 0; i < s.particles; ++i) {
        const int k = strip[t * s.particles + i];
        if (k < 0) continue;
        double q[kComponents];
        components_of(s, t, i, q);
        visit(i, out.strips[k], q);
      }
  };
  // Pass 1 ("during the averaging period"): strip means and centres.
  for (std::size_t t = 0; t < s.samples; ++t) {
    const double thickness = (s.strip_hi[t] - s.strip_lo[t]) / strips;
    for (int k = 0; k < strips; ++k) out.strips[k].centre += (s.strip_lo[t] + (k + 0.5) * thickness) / s.samples;
  }
  for_each_in_strips([&](std::size_t, StripMoments& m, const double* q) {
    ++m.count;
    for (int c = 0; c < kComponents; ++c) m.mean[c] += q[c];
  });
  for (auto& m : out.strips)
    if (m.count > 0)
      for (double& mean : m.mean) mean /= static_cast<double>(m.count);
  // Pass 2: the mean-square fluctuations about those means.
  for_each_in_strips([&](std::size_t i, StripMoments& m, const double* q) {
    for (int c = 0; c < kComponents; ++c) {
      const double d2 = (q[c] - m.mean[c]) * (q[c] - m.mean[c]);
      m.variance[c] += d2;
      m.energy[c] += weight(i, c) * d2;
    }
  });
  for (auto& m : out.strips)
    if (m.count > 0)
      for (int c = 0; c < kComponents; ++c) {
        m.variance[c] /= static_cast<double>(m.count);
        m.energy[c] /= static_cast<double>(m.count);
      }

  // Pass 3 ("the tape is rewound"): each particle sample in the selected strips against its strip.
  std::vector<std::vector<long long>> counts(out.variables.size(), std::vector<long long>(o.bins, 0));
  for (std::size_t t = 0; t < s.samples; ++t)
    for (std::size_t i = 0; i < s.particles; ++i) {
      const int k = strip[t * s.particles + i];
      if (k < out.first_strip || k > out.last_strip) continue;
      double q[kComponents];
      components_of(s, t, i, q);
      const auto& m = out.strips[k];
      ++out.counted;
      for (std::size_t v = 0; v < out.variables.size(); ++v) {
        auto& variable = out.variables[v];
        const bool single = variable.components.size() == 1;  // weights cancel: Campbell's X1-X3
        double energy = 0.0, mean_energy = 0.0;
        for (int c : variable.components) {
          const double w = single ? 1.0 : weight(i, c);
          energy += w * (q[c] - m.mean[c]) * (q[c] - m.mean[c]);
          mean_energy += single ? m.variance[c] : m.energy[c];
        }
        if (!(mean_energy > 0.0)) continue;
        const double x = std::sqrt(energy / mean_energy);
        if (x < o.x_max) ++counts[v][std::min(o.bins - 1, static_cast<int>(x / out.bin_width))];
        else ++variable.beyond;
      }
    }
  for (std::size_t v = 0; v < out.variables.size(); ++v) {
    auto& variable = out.variables[v];
    long long total = variable.beyond;
    for (long long n : counts[v]) total += n;
    variable.density.assign(o.bins, 0.0);
    if (total == 0) continue;
    for (int b = 0; b < o.bins; ++b)
      variable.density[b] = static_cast<double>(counts[v][b]) / (static_cast<double>(total) * out.bin_width);
    variable.fit = fit_generalized_maxwellian(static_cast<int>(variable.components.size()), out.x, out.bin_width,
                                              variable.density);
  }

  // S (Savage and Jeffrey): the gradient over the middle half of the selected strips (the no-slip
  // profile is linear there), the fluctuations pooled over all the selected strips.
  const int selected = out.last_strip - out.first_strip + 1;
  const int first = selected >= 4 ? out.first_strip + selected / 4 : out.first_strip;
  const int last = selected >= 4 ? out.last_strip - selected / 4 : out.last_strip;
  out.shear_rate = fitted_slope(out.strips, first, last);
  long long pooled = 0;
  for (int k = out.first_strip; k <= out.last_strip; ++k) {
    const auto& m = out.strips[k];
    pooled += m.count;
    out.u2 += m.count * m.variance[kU];
    out.v2 += m.count * m.variance[kV];
  }
  if (pooled > 0) {
    out.u2 /= static_cast<double>(pooled);
    out.v2 /= static_cast<double>(pooled);
  }
  if (out.u2 > 0.0) out.s_u = out.diameter * out.shear_rate / std::sqrt(out.u2);
  if (out.u2 + out.v2 > 0.0) out.s_uv = out.diameter * out.shear_rate / std::sqrt(out.u2 + out.v2);
  return out;
}

}  // namespace grainflow::analysis
