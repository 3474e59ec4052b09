#include "grainflow/observe/collision_stress.hpp"

#include <cmath>
#include <limits>

namespace grainflow::observe {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void add_outer(Tensor3& t, double weight, const Vec3& a, const Vec3& b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t[i * 3 + j] += weight * a[i] * b[j];
}

Tensor3 scaled(const Tensor3& t, double s) {
  Tensor3 out;
  for (int c = 0; c < 9; ++c) out[c] = t[c] * s;
  return out;
}

}  // namespace

StressProfile::Sums& StressProfile::Sums::operator+=(const Sums& o) {
  for (int c = 0; c < 9; ++c) {
    collisional[c] += o.collisional[c];
    second[c] += o.second[c];
  }
  momentum += o.momentum;
  mass += o.mass;
  number += o.number;
  collisions += o.collisions;
  collision_count += o.collision_count;
  dissipated += o.dissipated;
  return *this;
}

StressProfile::StressProfile(int strips, double period)
    : strips_(strips),
      period_(period),
      total_(strips),
      interval_(strips),
      momentum_start_(strips),
      momentum_end_(strips) {}

// With a periodic axis the segment is moved so that y0 lies in the strips; the parts beyond either
// end are visited again shifted by one period (a segment is shorter than the period, so the three
// copies cover disjoint parts of it and the fractions sum to 1).
template <class Visit>
void StressProfile::for_each_share(const StripGrid& grid, double y0, double y1, Visit&& visit) const {
  if (period_ <= 0.0) {
    grid.for_each_segment_part(y0, y1, visit);
    return;
  }
  const double shift = period_ * std::floor((y0 - grid.lo()) / period_);
  y0 -= shift;
  y1 -= shift;
  grid.for_each_segment_part(y0, y1, visit);
  if (y0 == y1) return;  // normal to the axis: counted whole where y0 lies
  grid.for_each_segment_part(y0 - period_, y1 - period_, visit);
  grid.for_each_segment_part(y0 + period_, y1 + period_, visit);
}

int StressProfile::strip_of(const StripGrid& grid, double y) const {
  if (period_ > 0.0) {
    y -= period_ * std::floor((y - grid.lo()) / period_);
    if (y >= grid.hi()) y = grid.lo();  // round-off at the top face
  }
  return grid.strip_of(y);
}

void StressProfile::begin(const StripGrid& grid, const ParticleStore& p, double time, const RankReduce& ranks) {
  started_ = true;
  start_time_ = last_time_ = time;
  interval_.assign(strips_, Sums{});
  std::fill(momentum_start_.begin(), momentum_start_.end(), Vec3{});
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.owned(i)) continue;
    if (const int k = strip_of(grid, p.position[i][grid.axis()]); k >= 0)
      momentum_start_[k] += p.mass[i] * p.velocity[i];
  }
  ranks.sum_records(momentum_start_);
  momentum_end_ = momentum_start_;
}

void StressProfile::add_segment(const StripGrid& grid, const Vec3& from, const Vec3& to, const Vec3& impulse) {
  const Vec3 branch = to - from;
  const double per_measure = 1.0 / grid.measure();
  for_each_share(grid, from[grid.axis()], to[grid.axis()], [&](int k, double fraction) {
    add_outer(interval_[k].collisional, fraction * per_measure, branch, impulse);
  });
}

void StressProfile::add(const StripGrid& grid, const engine_api::PairCollision& c) {
  if (!started_) return;
  add_segment(grid, c.xj, c.xi, c.impulse);
  if (const int k = strip_of(grid, c.contact[grid.axis()]); k >= 0) {
    Sums& s = interval_[k];
    s.collisions += 1.0 / grid.measure();
    s.collision_count += 1.0;
    s.dissipated += c.dissipated / grid.measure();
  }
}

void StressProfile::add(const StripGrid& grid, const engine_api::WallCollision& c) {
  if (!started_) return;
  add_segment(grid, c.contact, c.x, c.impulse);
}

void StressProfile::add_contact_force(const StripGrid& grid, const Vec3& centre, const Vec3& contact, const Vec3& force,
                                      double duration) {
  if (!started_) return;
  add_segment(grid, contact, centre, force * duration);
}

void StressProfile::sample(const StripGrid& grid, const ParticleStore& p, double time, const RankReduce& ranks) {
  if (!started_) return;
  const double per_measure = 1.0 / grid.measure();
  std::fill(momentum_end_.begin(), momentum_end_.end(), Vec3{});
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;  // fixed particles carry no kinetic stress; a ghost is its owner's
    const int k = strip_of(grid, p.position[i][grid.axis()]);
    if (k < 0) continue;
    const double m = p.mass[i];
    const Vec3& v = p.velocity[i];
    Sums& s = interval_[k];
    add_outer(s.second, m * per_measure, v, v);
    s.momentum += (m * per_measure) * v;
    s.mass += m * per_measure;
    s.number += 1.0;
    momentum_end_[k] += m * v;
  }
  ranks.sum_records(interval_);
  ranks.sum_records(momentum_end_);
  for (int k = 0; k < strips_; ++k) total_[k] += interval_[k];
  blocks_.add(interval_, time - last_time_);
  interval_.assign(strips_, Sums{});
  ++samples_;
  last_time_ = time;
  thickness_ = grid.thickness();
  measure_ = grid.measure();
  lo_ = grid.lo();
}

Tensor3 StressProfile::kinetic_of(const Sums& s, long samples, const Vec3& u) const {
  // sum m (v - u)(v - u) = sum m v v - P u - u P + M u u, with u fixed: linear in the sums, so the
  // blocks' values average to the long-term one.
  Tensor3 k = s.second;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) k[a * 3 + b] += -s.momentum[a] * u[b] - u[a] * s.momentum[b] + s.mass * u[a] * u[b];
  return scaled(k, 1.0 / samples);
}

std::vector<StripStress> StressProfile::averages(const Vec3& gravity, const Vec3& top_row) const {
  std::vector<StripStress> out(strips_);
  const double span = elapsed();
  const auto& blocks = blocks_.blocks();
  const auto& durations = blocks_.block_weights();
  for (int k = 0; k < strips_; ++k) {
    StripStress& a = out[k];
    a.lo = lo_ + k * thickness_;
    a.hi = a.lo + thickness_;
    if (samples_ == 0 || !(span > 0.0)) {
      a.collisional.fill(kNaN);
      a.kinetic.fill(kNaN);
      a.total.fill(kNaN);
      a.collisional_error.fill(kNaN);
      a.kinetic_error.fill(kNaN);
      a.total_error.fill(kNaN);
      a.collision_rate = a.collision_rate_per_particle = a.dissipation_rate = a.number = a.mass_density = kNaN;
      a.mean_velocity = a.momentum_rate = a.weight_row = Vec3{kNaN, kNaN, kNaN};
      continue;
    }
    const Sums& s = total_[k];
    const Vec3 u = s.mass > 0.0 ? s.momentum * (1.0 / s.mass) : Vec3{};
    a.collisional = scaled(s.collisional, 1.0 / span);
    a.kinetic = kinetic_of(s, samples_, u);
    for (int c = 0; c < 9; ++c) a.total[c] = a.collisional[c] + a.kinetic[c];
    for (int c = 0; c < 9; ++c) {
      std::vector<double> coll, kin, tot;
      for (std::size_t b = 0; b < blocks.size(); ++b) {
        const double cb = blocks[b][k].collisional[c] / durations[b];
        const double kb = kinetic_of(blocks[b][k], blocks_.block_length(), u)[c];
        coll.push_back(cb);
        kin.push_back(kb);
        tot.push_back(cb + kb);
      }
      a.collisional_error[c] = blocked_standard_error(coll);
      a.kinetic_error[c] = blocked_standard_error(kin);
      a.total_error[c] = blocked_standard_error(tot);
    }
    a.collision_rate = s.collisions / span;
    a.number = s.number / samples_;
    a.collision_rate_per_particle = a.number > 0.0 ? 2.0 * s.collision_count / span / a.number : 0.0;
    a.dissipation_rate = s.dissipated / span;
    a.mass_density = s.mass / samples_;
    a.mean_velocity = u;
    a.momentum_rate = (momentum_end_[k] - momentum_start_[k]) * (1.0 / (span * measure_));
  }
  // Campbell's weight integral, down from the top: a strip's momentum changes by the flux in at its
  // lower face, out at its upper one, and its weight: P(y_k) = P(y_k+1) + h (dp/dt - rho g).
  Vec3 above = top_row;
  for (int k = strips_ - 1; k >= 0 && samples_ > 0 && span > 0.0; --k) {
    const Vec3 change = thickness_ * (out[k].momentum_rate - out[k].mass_density * gravity);
    out[k].weight_row = above + 0.5 * change;
    above += change;
  }
  return out;
}

}  // namespace grainflow::observe
