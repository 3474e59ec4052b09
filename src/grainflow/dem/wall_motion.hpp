// Motion of a wall: a constant velocity plus the vibrating drive of section 2.6.4,
// v_k = s(t) A_k 2 pi f_k cos(2 pi f_k (t - start) + phi_k), with s ramping linearly from 0 to 1
// over `ramp` seconds after `start`. The displacement is the exact integral of that velocity,
// so position and velocity of the floor are always consistent. A controller (the Couette servo) may
// steer the wall: from a time on, a further constant velocity, its displacement continuing from
// where the wall then was.
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
  const Vec3& constant_velocity() const { return constant_velocity_; }

  // From time t on, the wall moves with `velocity` in addition to its constant and driven motion.
  void steer(double t, const Vec3& velocity) {
    steered_displacement_ = steered_displacement(t);
    steered_since_ = t;
    steered_velocity_ = velocity;
  }
  const Vec3& steered_velocity() const { return steered_velocity_; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(steered_velocity_, steered_displacement_, steered_since_);
  }

 private:
  Vec3 steered_displacement(double t) const { return steered_displacement_ + steered_velocity_ * (t - steered_since_); }

  Vec3 constant_velocity_;
  DriveConfig drive_;
  Vec3 steered_velocity_, steered_displacement_;  // m/s, m: the controller's part
  double steered_since_ = 0.0;                    // s
};

}  // namespace grainflow::dem
