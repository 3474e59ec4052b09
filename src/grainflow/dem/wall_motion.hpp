// Motion of a wall: a constant velocity plus the vibrating drive of section 2.6.4,
// v_k = s(t) A_k 2 pi f_k cos(2 pi f_k (t - start) + phi_k), with s ramping linearly from 0 to 1
// over `ramp` seconds after `start`. The displacement is the exact integral of that velocity,
// so position and velocity of the floor are always consistent.
#pragma once

#include "grainflow/config/case_config.hpp"

namespace grainflow::dem {

class WallMotion {
 public:
  WallMotion() = default;
  WallMotion(const Vec3& constant_velocity, const DriveConfig* drive)
      : constant_velocity_(constant_velocity), drive_(drive ? *drive : DriveConfig{}) {}

  Vec3 velocity(double t) const;      // m/s
  Vec3 displacement(double t) const;  // m, from the position at t = 0
  bool moves() const { return drive_.enabled || constant_velocity_ != Vec3{}; }

 private:
  Vec3 constant_velocity_;
  DriveConfig drive_;
};

}  // namespace grainflow::dem
