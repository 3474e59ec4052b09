#include "grainflow/analysis/pair_distribution.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "grainflow/analysis/block_average.hpp"

namespace grainflow::analysis {
namespace {

double nearest_image(double d, double period) { return period > 0.0 ? d - period * std::nearbyint(d / period) : d; }

// The slice of a distance known to lie in [0, range) (round-off cannot push it to `slices`).
int slice_of(double distance, double h, int slices) { return std::min(slices - 1, static_cast<int>(distance / h)); }

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One distribution's per-sample counts and region measures, slice by slice.
struct SliceSeries {
  std::vector<std::vector<double>> count, measure;  // [slice][sample]

  SliceSeries(int slices, std::size_t samples)
      : count(slices, std::vector<double>(samples, 0.0)), measure(slices, std::vector<double>(samples, 0.0)) {}

  // Density = sum c / sum m; its error from the linearised ratio: y_t = d + (c_t - d m_t) / mean m,
  // whose mean is d, block-averaged over the samples.
  void finish(std::vector<double>& density, std::vector<double>& error) const {
    for (std::size_t k = 0; k < count.size(); ++k) {
      double c = 0.0, m = 0.0;
      for (double x : count[k]) c += x;
      for (double x : measure[k]) m += x;
      if (!(m > 0.0)) {
        density.push_back(kNaN);
        error.push_back(kNaN);
        continue;
      }
      const double d = c / m, samples = static_cast<double>(count[k].size()), mean_measure = m / samples;
      density.push_back(d);
      if (count[k].size() < 2) {
        error.push_back(kNaN);
        continue;
      }
      std::vector<double> y(count[k].size());
      for (std::size_t t = 0; t < y.size(); ++t) y[t] = d + (count[k][t] - d * measure[k][t]) / mean_measure;
      error.push_back(block_average(y).standard_error);
    }
  }
};

}  // namespace

PairDistributions pair_distributions(const StateSamples& s, const PairDistributionOptions& o) {
  PairDistributions out;
  const int slices = o.slices;
  out.diameter = 2.0 * s.mean_radius();
  const double d = out.diameter;
  const double range = o.range > 0.0 ? o.range : 4.0 * d;
  const double h = range / slices;
  out.slice = h;
  for (int k = 0; k < slices; ++k) out.r.push_back((k + 0.5) * h);
  const bool periodic_y = s.period_y > 0.0, three = s.dimension == 3;
  const double depth = three ? s.box_depth : 1.0;
  // In 3D the parallel tube reaches one diameter either side in z too (clipped to the box).
  const double period_z = three && s.periodic_z ? s.box_depth : 0.0;
  auto tube_z = [&](double z) {
    if (!three) return 1.0;
    if (s.periodic_z) return std::min(2.0 * d, s.box_depth);
    return overlap_length(z - d, z + d, s.z_lo, s.z_lo + s.box_depth);
  };
  SliceSeries normal(slices, s.samples), parallel(slices, s.samples), two_sided(slices, s.samples);
  long long tests = 0;
  for (std::size_t t = 0; t < s.samples; ++t) {
    const double width = s.box_width[t];
    const double lo = periodic_y ? -std::numeric_limits<double>::infinity() : s.wall_lo[t];
    const double hi = periodic_y ? std::numeric_limits<double>::infinity() : s.wall_hi[t];
    const double gap = periodic_y ? s.period_y : hi - lo, mid = 0.5 * (lo + hi);
    out.number_density += static_cast<double>(s.particles) / (gap * width * depth) / s.samples;
    long long band = 0;
    for (std::size_t i = 0; i < s.particles; ++i) {
      const double* xi = s.at(s.position, t, i);
      if (!periodic_y && !(std::fabs(xi[1] - mid) < d)) continue;
      ++band;
      // The measure each slice covers around this test particle.
      const double layer = (periodic_y ? 2.0 * d : overlap_length(xi[1] - d, xi[1] + d, lo, hi)) * tube_z(xi[2]);
      for (int k = 0; k < slices; ++k) {
        const double a = k * h, b = a + h;
        const double across =
            periodic_y ? 2.0 * overlap_length(a, b, 0.0, 0.5 * s.period_y)
                       : overlap_length(xi[1] + a, xi[1] + b, lo, hi) + overlap_length(xi[1] - b, xi[1] - a, lo, hi);
        normal.measure[k][t] += across * width * depth;
        parallel.measure[k][t] += overlap_length(a, b, 0.0, width) * layer;
        two_sided.measure[k][t] += 2.0 * overlap_length(a, b, 0.0, 0.5 * width) * layer;
      }
      for (std::size_t j = 0; j < s.particles; ++j) {
        if (j == i) continue;
        const double* xj = s.at(s.position, t, j);
        const double dy = std::fabs(nearest_image(xj[1] - xi[1], s.period_y));
        if (dy < range) normal.count[slice_of(dy, h, slices)][t] += 1.0;
        if (!(dy < d)) continue;
        if (three && !(std::fabs(nearest_image(xj[2] - xi[2], period_z)) < d)) continue;
        const double forward = xj[0] - xi[0] - width * std::floor((xj[0] - xi[0]) / width);
        if (forward < range) parallel.count[slice_of(forward, h, slices)][t] += 1.0;
        const double nearest = std::min(forward, width - forward);
        if (nearest < range) two_sided.count[slice_of(nearest, h, slices)][t] += 1.0;
      }
    }
    tests += band;
    const double band_measure =
        periodic_y ? gap * width * depth : overlap_length(mid - d, mid + d, lo, hi) * width * depth;
    out.band_number_density += static_cast<double>(band) / band_measure / s.samples;
  }
  out.test_particles_per_sample = s.samples > 0 ? static_cast<double>(tests) / s.samples : 0.0;
  normal.finish(out.normal, out.normal_error);
  parallel.finish(out.parallel, out.parallel_error);
  two_sided.finish(out.parallel_two_sided, out.parallel_two_sided_error);
  return out;
}

}  // namespace grainflow::analysis
