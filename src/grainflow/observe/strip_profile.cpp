#include "grainflow/observe/strip_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace grainflow::observe {

StripProfile::StripProfile(int dimension, int count)
    : dimension_(dimension), sums_(std::max(1, count)), scratch_(std::max(1, count)) {}

StripProfile::Sums& StripProfile::Sums::operator+=(const Sums& o) {
  solids_fraction += o.solids_fraction;
  centre += o.centre;
  mass += o.mass;
  particles += o.particles;
  inertia += o.inertia;
  momentum += o.momentum;
  second_moment += o.second_moment;
  cross += o.cross;
  mass_spin += o.mass_spin;
  inertia_spin += o.inertia_spin;
  spin_second += o.spin_second;
  fluctuation_lan += o.fluctuation_lan;
  samples += o.samples;
  return *this;
}

void StripProfile::sample(const ParticleStore& p, const StripGrid& grid) {
  const int axis = grid.axis();
  const double measure = grid.measure();
  std::fill(scratch_.begin(), scratch_.end(), Sums{});
  // Pass 1: shares of solid measure, mass, momentum and spin in each strip.
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] != Motion::free) continue;
    const Vec3 w = p.angular_velocity[i];
    const double inertia = p.inv_inertia[i] > 0.0 ? 1.0 / p.inv_inertia[i] : 0.0;
    grid.for_each_overlap(p.position[i][axis], p.radius[i],
                          [&](int k, double part, double fraction, const Vec3& shift) {
                            Sums& s = scratch_[k];
                            const Vec3 v = p.velocity[i] + shift;  // across a Lees-Edwards seam, the image's velocity
                            const double m = p.mass[i] * fraction, moment = inertia * fraction;
                            s.solids_fraction += part / measure;
                            s.mass += m;
                            s.particles += fraction;
                            s.inertia += moment;
                            s.momentum += m * v;
                            s.second_moment += Vec3{m * v.x * v.x, m * v.y * v.y, m * v.z * v.z};
                            s.cross += m * v.x * v.y;
                            s.mass_spin += m * w;
                            s.inertia_spin += moment * w;
                            s.spin_second += moment * norm2(w);
                          });
  }
  // Pass 2: Lan's fluctuations about each strip's mean velocity at this instant.
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] != Motion::free) continue;
    grid.for_each_overlap(p.position[i][axis], p.radius[i], [&](int k, double, double fraction, const Vec3& shift) {
      Sums& s = scratch_[k];
      const Vec3 dv = p.velocity[i] + shift - s.momentum * (1.0 / s.mass);
      double sum = 0.0;
      for (int a = 0; a < dimension_; ++a) sum += dv[a] * dv[a];
      s.fluctuation_lan += p.mass[i] * fraction * sum;
    });
  }
  for (int k = 0; k < count(); ++k) {
    scratch_[k].centre = grid.centre(k);
    scratch_[k].samples = 1;
    sums_[k] += scratch_[k];
  }
  ++samples_;
  blocks_.add(scratch_);
}

std::array<double, strip::kQuantities> StripProfile::values_of(const Sums& s) const {
  using namespace strip;
  std::array<double, kQuantities> x{};
  if (s.samples == 0) {
    x.fill(std::numeric_limits<double>::quiet_NaN());
    return x;
  }
  x[solids_fraction] = s.solids_fraction / s.samples;
  x[mass] = s.mass / s.samples;
  x[particles] = s.particles / s.samples;
  if (!(s.mass > 0.0)) {
    std::fill(x.begin() + u, x.end(), std::numeric_limits<double>::quiet_NaN());
    return x;
  }
  const double per_mass = 1.0 / s.mass;
  const Vec3 mean = s.momentum * per_mass;
  double translational = 0.0;
  for (int a = 0; a < 3; ++a) {
    x[u + a] = mean[a];
    x[u_variance + a] = std::max(0.0, s.second_moment[a] * per_mass - mean[a] * mean[a]);
    if (a < dimension_) translational += x[u_variance + a];
  }
  x[uv_covariance] = s.cross * per_mass - mean.x * mean.y;
  // beta <|omega'|^2> = sum I |omega - <omega>|^2 / sum m, expanded into the accumulated sums.
  const Vec3 spin = s.mass_spin * per_mass;
  for (int a = 0; a < 3; ++a) x[omega_x + a] = spin[a];
  const int rotational_freedoms = dimension_ == 2 ? 1 : 3;
  const double spin_fluctuation =
      std::max(0.0, s.spin_second - 2.0 * dot(spin, s.inertia_spin) + norm2(spin) * s.inertia);
  x[rotational_temperature] = spin_fluctuation * per_mass / rotational_freedoms;
  x[granular_temperature] = translational / dimension_;
  const double particle_mass = s.mass / s.particles;
  x[translational_temperature] = 0.5 * particle_mass * translational;
  x[temperature] = 0.5 * particle_mass * (translational + spin_fluctuation * per_mass);
  x[temperature_lan] = s.fluctuation_lan * per_mass / dimension_;
  return x;
}

std::vector<StripAverages> StripProfile::averages() const {
  std::vector<StripAverages> out(sums_.size());
  const auto& blocks = blocks_.blocks();
  for (std::size_t k = 0; k < sums_.size(); ++k) {
    StripAverages& a = out[k];
    const Sums& s = sums_[k];
    a.centre = s.samples > 0 ? s.centre / s.samples : 0.0;
    a.relative_centre = (k + 0.5) / sums_.size();
    a.value = values_of(s);
    // Each quantity's per-block values; blocks without mass have no velocity and are left out.
    std::array<std::vector<double>, strip::kQuantities> per_block;
    for (const auto& block : blocks) {
      const auto x = values_of(block[k]);
      for (int q = 0; q < strip::kQuantities; ++q)
        if (std::isfinite(x[q])) per_block[q].push_back(x[q]);
    }
    for (int q = 0; q < strip::kQuantities; ++q) a.error[q] = blocked_standard_error(per_block[q]);
  }
  return out;
}

}  // namespace grainflow::observe
