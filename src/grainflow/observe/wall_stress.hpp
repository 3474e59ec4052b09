// The load the particles put on each wall of an event-driven run (Campbell 1982 sections 2.14.3,
// 3.3): normal and shear stress from the collisions' impulses per unit wall area and time, plus the
// continuous push of particles rolling on it (sampled), the impulse angle, collision and
// dissipation rates, with block-averaged error bars.
//
// Convention as for the strips (observe/collision_stress.hpp): the wall's row of the pressure
// tensor, P_ab = n_a t_b, with t the traction the wall exerts on the particles and n its unit
// normal into the box (a the wall's axis). The normal stress P_aa = n.t is compressive positive;
// the shear stress P_af, f the flow direction (x; y for a wall normal to x), equals the strips'
// P_yx next to a y wall, so it is negative where the flow's speed grows with y.
#pragma once

#include <vector>

#include "grainflow/core/vec3.hpp"
#include "grainflow/engine_api/collision_observer.hpp"
#include "grainflow/observe/block_sums.hpp"
#include "grainflow/observe/rank_reduce.hpp"

namespace grainflow::observe {

struct WallLoad {
  double normal_stress = 0.0, normal_stress_error = 0.0;  // Pa (2D: N/m)
  double shear_stress = 0.0, shear_stress_error = 0.0;    // Pa (2D: N/m)
  double friction = 0.0;                                  // shear_stress / normal_stress
  double impulse_angle_deg = 0.0;                         // atan2(shear_stress, normal_stress), degrees
  double rolling_normal_stress = 0.0;  // the parts of the stresses from particles rolling on the wall
  double rolling_shear_stress = 0.0;
  double collision_rate = 0.0;    // 1/(s m^(D-1))
  double dissipation_rate = 0.0;  // W/m^(D-1)
  long long collisions = 0;
  Vec3 row;  // P_ab at the wall, b = x, y, z
};

class WallLoads {
 public:
  // Any plane walls with the wall's normal axis and `inward` sign (+1 on a lo face): the
  // event-driven engine's and the soft-sphere engine's alike.
  template <class Walls>
  explicit WallLoads(const Walls& walls) : total_(walls.size()), interval_(walls.size()) {
    for (const auto& w : walls) {
      axis_.push_back(w.axis);
      inward_.push_back(w.inward);
    }
  }

  // `area`: the wall's current area (2D: length), m^(D-1).
  void add(const engine_api::WallCollision& c, double area);
  // A rolling particle's push, `force` on the particle, through `duration`.
  void add_rolling(int wall, const Vec3& force, double duration, double area);
  // Ends a sample interval; on several MPI ranks (`ranks`) its sums are first added over them.
  void close_interval(double duration, const RankReduce& ranks = {});

  double elapsed() const { return elapsed_; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(total_, interval_, blocks_, elapsed_);
  }
  std::vector<WallLoad> averages() const;

  static int flow_axis(int wall_axis) { return wall_axis == 0 ? 1 : 0; }

 private:
  struct Sums {
    Vec3 impulse;             // kg m/s per m^(D-1): collisions' impulses on the particles / area
    Vec3 rolling;             // the same from rolling particles
    double collisions = 0.0;  // per m^(D-1)
    double count = 0.0;
    double dissipated = 0.0;  // J per m^(D-1)
    Sums& operator+=(const Sums& o);
  };
  Vec3 row_of(int w, const Vec3& traction) const;

  std::vector<int> axis_;
  std::vector<double> inward_;
  std::vector<Sums> total_, interval_;
  BlockSums<Sums> blocks_;  // per interval, weighted by its duration
  double elapsed_ = 0.0;
};

}  // namespace grainflow::observe
