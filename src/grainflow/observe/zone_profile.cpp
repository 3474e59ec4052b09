#include "grainflow/observe/zone_profile.hpp"

#include <algorithm>
#include <cmath>

#include "grainflow/core/ball_measure.hpp"

namespace grainflow::observe {

ZoneProfile::ZoneProfile(int axis, double lo, double hi, double thickness, double cross_section_area, int dimension)
    : axis_(axis), dimension_(dimension), lo_(lo), hi_(hi), thickness_(thickness) {
  const int zones = std::max(1, static_cast<int>(std::ceil((hi - lo) / thickness - 1e-9)));
  sums_.resize(zones);
  scratch_.resize(zones);
  fluctuations_.resize(zones);
  for (int z = 0; z < zones; ++z) {
    const double top = std::min(hi, lo + (z + 1) * thickness);
    zone_volume_.push_back((top - (lo + z * thickness)) * cross_section_area);
  }
}

// Calls visit(zone, partial volume, fraction of the sphere, velocity) for each zone free particle i
// overlaps. Along a periodic axis the sphere is first brought into [lo, hi) (a sphere not yet wrapped
// since it crossed the seam), and the share beyond either end counts at the other as its image.
template <class Visit>
void ZoneProfile::for_each_overlap(const ParticleStore& p, std::size_t i, Visit&& visit) const {
  const double r = p.radius[i];
  const double whole = ball_measure(dimension_, r);
  double c = p.position[i][axis_];
  Vec3 v = p.velocity[i];
  if (period_ > 0.0) {
    const double turns = std::floor((c - lo_) / period_);
    c -= turns * period_;
    v -= turns * image_velocity_;
    if (c - r < lo_) overlap_at(c + period_, r, whole, v + image_velocity_, visit);
    if (c + r > hi_) overlap_at(c - period_, r, whole, v - image_velocity_, visit);
  }
  overlap_at(c, r, whole, v, visit);
}

template <class Visit>
void ZoneProfile::overlap_at(double c, double r, double whole, const Vec3& v, Visit& visit) const {
  const int zones = static_cast<int>(sums_.size());
  const int first = std::max(0, static_cast<int>(std::floor((c - r - lo_) / thickness_)));
  const int last = std::min(zones - 1, static_cast<int>(std::floor((c + r - lo_) / thickness_)));
  for (int z = first; z <= last; ++z) {
    const double a = lo_ + z * thickness_;
    const double part = particle_slab_measure(dimension_, r, c, a, std::min(hi_, a + thickness_));
    if (part > 0.0) visit(z, part, part / whole, v);
  }
}

// Pass 1 of a sample: partial volumes, mass and momentum per zone, into scratch_.
void ZoneProfile::fill_masses(const ParticleStore& p) {
  std::fill(scratch_.begin(), scratch_.end(), Sums{});
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;
    for_each_overlap(p, i, [&](int z, double part, double fraction, const Vec3& v) {
      const double m = p.mass[i] * fraction;
      scratch_[z].solid_volume += part;
      scratch_[z].mass += m;
      scratch_[z].momentum += m * v;
    });
  }
  reduce(scratch_);
}

void ZoneProfile::reduce(std::vector<Sums>& sums) const {
  static_assert(sizeof(Sums) == 11 * sizeof(double), "Sums must be plain doubles to be summed over MPI ranks");
  reduce_.sum(reinterpret_cast<double*>(sums.data()), sums.size() * 11);
}

std::vector<Vec3> ZoneProfile::instantaneous_mean_velocity(const ParticleStore& p) {
  fill_masses(p);
  std::vector<Vec3> u(scratch_.size());
  for (std::size_t z = 0; z < u.size(); ++z)
    if (scratch_[z].mass > 0.0) u[z] = scratch_[z].momentum * (1.0 / scratch_[z].mass);
  return u;
}

std::vector<double> ZoneProfile::zone_centres() const {
  std::vector<double> centre(sums_.size());
  for (std::size_t z = 0; z < centre.size(); ++z)
    centre[z] = 0.5 * (lo_ + z * thickness_ + std::min(hi_, lo_ + (z + 1) * thickness_));
  return centre;
}

// Pass 2 of a sample: fluctuations about the instantaneous zone mean and second moments, into scratch_.
// (Summed apart from pass 1's sums, so that reducing them over ranks does not count those twice.)
void ZoneProfile::fill_fluctuations(const ParticleStore& p) {
  std::fill(fluctuations_.begin(), fluctuations_.end(), Sums{});
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;
    for_each_overlap(p, i, [&](int z, double, double fraction, const Vec3& v) {
      const double m = p.mass[i] * fraction;
      const Vec3 u = scratch_[z].momentum * (1.0 / scratch_[z].mass);
      const Vec3 dv = v - u;
      fluctuations_[z].fluctuation_lan += Vec3{m * dv.x * dv.x, m * dv.y * dv.y, m * dv.z * dv.z};
      fluctuations_[z].second_moment += Vec3{m * v.x * v.x, m * v.y * v.y, m * v.z * v.z};
    });
  }
  reduce(fluctuations_);
  for (std::size_t z = 0; z < scratch_.size(); ++z) {
    scratch_[z].fluctuation_lan += fluctuations_[z].fluctuation_lan;
    scratch_[z].second_moment += fluctuations_[z].second_moment;
  }
}

ZoneProfile::Sums& ZoneProfile::Sums::operator+=(const Sums& o) {
  mass += o.mass;
  solid_volume += o.solid_volume;
  momentum += o.momentum;
  second_moment += o.second_moment;
  fluctuation_lan += o.fluctuation_lan;
  return *this;
}

double ZoneProfile::instantaneous_temperature(const ParticleStore& p) {
  fill_masses(p);
  fill_fluctuations(p);
  double mass = 0.0, fluctuation = 0.0;
  for (const Sums& s : scratch_) {
    mass += s.mass;
    fluctuation += s.fluctuation_lan.x + s.fluctuation_lan.y + s.fluctuation_lan.z;
  }
  return mass > 0.0 ? fluctuation / (dimension_ * mass) : 0.0;
}

void ZoneProfile::sample(const ParticleStore& p) {
  fill_masses(p);
  fill_fluctuations(p);
  for (std::size_t z = 0; z < sums_.size(); ++z) sums_[z] += scratch_[z];
  ++samples_;
  blocks_.add(scratch_);
}

std::vector<ZoneAverages> ZoneProfile::averages() const {
  std::vector<ZoneAverages> out(sums_.size());
  for (std::size_t z = 0; z < sums_.size(); ++z) {
    ZoneAverages& a = out[z];
    a.lo = lo_ + z * thickness_;
    a.hi = std::min(hi_, a.lo + thickness_);
    if (samples_ == 0) continue;
    const Sums& s = sums_[z];
    a.solids_fraction = s.solid_volume / (zone_volume_[z] * samples_);
    a.mass = s.mass / samples_;
    a.kinetic_energy_density =
        0.5 * (s.fluctuation_lan.x + s.fluctuation_lan.y + s.fluctuation_lan.z) / (zone_volume_[z] * samples_);
    if (s.mass <= 0.0) continue;
    a.mean_velocity = s.momentum * (1.0 / s.mass);
    a.temperature_lan = s.fluctuation_lan * (1.0 / s.mass);
    for (int axis = 0; axis < 3; ++axis)
      a.temperature_time_mean[axis] =
          std::max(0.0, s.second_moment[axis] / s.mass - a.mean_velocity[axis] * a.mean_velocity[axis]);
  }
  add_errors(out);
  return out;
}

void ZoneProfile::add_errors(std::vector<ZoneAverages>& out) const {
  for (std::size_t z = 0; z < out.size(); ++z) {
    std::vector<double> nu, lan, time_mean;
    std::array<std::vector<double>, 3> u;
    for (const auto& block : blocks_.blocks()) {
      const Sums& s = block[z];
      nu.push_back(s.solid_volume / (zone_volume_[z] * blocks_.block_length()));
      if (s.mass <= 0.0) continue;  // velocity and temperature are undefined in an empty block
      double tm = 0.0;
      for (int axis = 0; axis < 3; ++axis) {
        const double mean = s.momentum[axis] / s.mass;
        u[axis].push_back(mean);
        tm += std::max(0.0, s.second_moment[axis] / s.mass - mean * mean) / dimension_;
      }
      lan.push_back((s.fluctuation_lan.x + s.fluctuation_lan.y + s.fluctuation_lan.z) / (dimension_ * s.mass));
      time_mean.push_back(tm);
    }
    ZoneAverages& a = out[z];
    a.solids_fraction_error = blocked_standard_error(nu);
    for (int axis = 0; axis < 3; ++axis) a.mean_velocity_error[axis] = blocked_standard_error(u[axis]);
    a.temperature_lan_error = blocked_standard_error(lan);
    a.temperature_time_mean_error = blocked_standard_error(time_mean);
  }
}

}  // namespace grainflow::observe
