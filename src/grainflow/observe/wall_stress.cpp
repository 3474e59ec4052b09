#include "grainflow/observe/wall_stress.hpp"

#include <cmath>
#include <limits>

namespace grainflow::observe {

WallLoads::Sums& WallLoads::Sums::operator+=(const Sums& o) {
  impulse += o.impulse;
  rolling += o.rolling;
  collisions += o.collisions;
  count += o.count;
  dissipated += o.dissipated;
  return *this;
}

void WallLoads::add(const engine_api::WallCollision& c, double area) {
  Sums& s = interval_[c.wall];
  s.impulse += c.impulse * (1.0 / area);
  s.collisions += 1.0 / area;
  s.count += 1.0;
  s.dissipated += c.dissipated / area;
}

void WallLoads::add_rolling(int wall, const Vec3& force, double duration, double area) {
  interval_[wall].rolling += force * (duration / area);
}

void WallLoads::close_interval(double duration, const RankReduce& ranks) {
  ranks.sum_records(interval_);
  for (std::size_t w = 0; w < total_.size(); ++w) total_[w] += interval_[w];
  blocks_.add(interval_, duration);
  interval_.assign(total_.size(), Sums{});
  elapsed_ += duration;
}

Vec3 WallLoads::row_of(int w, const Vec3& traction) const { return inward_[w] * traction; }

std::vector<WallLoad> WallLoads::averages() const {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::vector<WallLoad> out(total_.size());
  for (std::size_t w = 0; w < out.size(); ++w) {
    WallLoad& a = out[w];
    const Sums& s = total_[w];
    const int n = axis_[w], f = flow_axis(axis_[w]);
    a.collisions = static_cast<long long>(s.count);
    if (!(elapsed_ > 0.0)) {
      a.normal_stress = a.normal_stress_error = a.shear_stress = a.shear_stress_error = kNaN;
      a.friction = a.impulse_angle_deg = a.rolling_normal_stress = a.rolling_shear_stress = kNaN;
      a.collision_rate = a.dissipation_rate = kNaN;
      a.row = Vec3{kNaN, kNaN, kNaN};
      continue;
    }
    a.row = row_of(static_cast<int>(w), (s.impulse + s.rolling) * (1.0 / elapsed_));
    const Vec3 rolling = row_of(static_cast<int>(w), s.rolling * (1.0 / elapsed_)) + Vec3{};  // + 0: no "-0" for none
    a.normal_stress = a.row[n];
    a.shear_stress = a.row[f];
    a.rolling_normal_stress = rolling[n];
    a.rolling_shear_stress = rolling[f];
    a.friction = a.normal_stress != 0.0 ? a.shear_stress / a.normal_stress : kNaN;
    a.impulse_angle_deg = std::atan2(a.shear_stress, a.normal_stress) * 180.0 / M_PI;
    a.collision_rate = s.collisions / elapsed_;
    a.dissipation_rate = s.dissipated / elapsed_;
    std::vector<double> normal, shear;
    const auto& blocks = blocks_.blocks();
    for (std::size_t b = 0; b < blocks.size(); ++b) {
      const Vec3 row = row_of(static_cast<int>(w),
                              (blocks[b][w].impulse + blocks[b][w].rolling) * (1.0 / blocks_.block_weights()[b]));
      normal.push_back(row[n]);
      shear.push_back(row[f]);
    }
    a.normal_stress_error = blocked_standard_error(normal);
    a.shear_stress_error = blocked_standard_error(shear);
  }
  return out;
}

}  // namespace grainflow::observe
