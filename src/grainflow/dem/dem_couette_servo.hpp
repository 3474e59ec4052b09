// Campbell's pressure-controlled Couette cell for soft particles: the flat walls at ylo and yhi move
// apart or together along y so that the normal stress the particles exert on them approaches its
// target, by the event-driven engine's rule (config/couette_servo_rule.hpp): an update after
// `every_collisions` contacts begun between particles or once the gap has changed by `gap_change`,
// the walls' normal impulse since the last update (the contact forces integrated over the steps by
// the trapezoidal rule) giving the measured stress; and, if `interval` is set, once that long has
// passed (a packing at rest begins few contacts and its gap may not move). The walls are steered (WallMotion::steer)
// from the update on, so their positions stay continuous. The periodic width stays the box's.
#pragma once

#include <cmath>
#include <stdexcept>

#include "grainflow/config/couette_servo_rule.hpp"
#include "grainflow/dem/dem_state.hpp"

namespace grainflow::dem {

class DemCouetteServo {
 public:
  DemCouetteServo() = default;
  explicit DemCouetteServo(const DemState& s) {
    if (!s.servo.config.enabled) return;
    bottom_ = wall_with_role(s.walls, WallRole::shear_bottom);
    top_ = wall_with_role(s.walls, WallRole::shear_top);
    if (bottom_ < 0 || top_ < 0) throw std::invalid_argument("DemCouetteServo: the servo needs walls at ylo and yhi");
    gap_ = gap(s);
    shear_rate_ = (s.walls[top_].velocity.x - s.walls[bottom_].velocity.x) / gap_;
    since_ = s.time;
    state_ = {gap_, s.box.length(0), 0.0, 0.0, s.walls[top_].velocity.x};
  }

  bool enabled() const { return bottom_ >= 0; }
  int bottom_wall() const { return bottom_; }
  int top_wall() const { return top_; }
  double gap(const DemState& s) const { return s.walls[top_].position - s.walls[bottom_].position; }
  const CouetteServoState& state() const { return state_; }
  long long updates() const { return updates_; }

  // The normal forces the particles exert on the two walls now (N; N/m for discs), after a step of dt.
  void add_loads(double dt, double bottom_load, double top_load) {
    impulse_ += 0.5 * dt * (last_load_ + bottom_load + top_load);
    last_load_ = bottom_load + top_load;
  }
  // The loads at the start (before the first step), so that the first step's trapezoid has both ends.
  void start_loads(double bottom_load, double top_load) { last_load_ = bottom_load + top_load; }

  bool due(const DemState& s, long long collisions) const {
    const ServoConfig& servo = s.servo.config;
    return collisions - collisions_ >= servo.every_collisions || std::fabs(gap(s) - gap_) >= servo.gap_change ||
           (servo.interval > 0.0 && s.time - since_ >= servo.interval * (1.0 - 1e-12));
  }

  // New wall speeds from the stress measured since the last update, the walls steered from now.
  void update(DemState& s, long long collisions) {
    const double span = s.time - since_;
    if (span <= 0.0) return;
    double area = s.box.length(0);
    if (s.dimension == 3) area *= s.box.length(2);
    const double stress = 0.5 * impulse_ / (span * area);
    const double speed = s.servo.wall_speed(state_.wall_speed, stress);
    DemWall& bottom = s.walls[bottom_];
    DemWall& top = s.walls[top_];
    double bottom_x = bottom.velocity.x, top_x = top.velocity.x;
    const double now_gap = gap(s);
    if (s.servo.config.keep_shear_rate) s.servo.keep_shear_rate(bottom_x, top_x, shear_rate_ * now_gap);
    steer(bottom, s.time, {bottom_x, -speed, bottom.velocity.z});
    steer(top, s.time, {top_x, speed, top.velocity.z});
    state_ = {now_gap, s.box.length(0), speed, stress, top_x};
    impulse_ = 0.0;
    since_ = s.time;
    gap_ = now_gap;
    collisions_ = collisions;
    ++updates_;
  }

  // Between updates: the gap now (the outputs read it).
  void observe(const DemState& s) { state_.gap = gap(s); }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(impulse_, last_load_, since_, gap_, collisions_, updates_, state_.gap, state_.width, state_.wall_speed,
       state_.measured_stress, state_.top_speed);
  }

 private:
  // The wall moves at `velocity` from t on: its constant velocity (the case's) plus the steered part.
  static void steer(DemWall& wall, double t, const Vec3& velocity) {
    wall.motion.steer(t, velocity - wall.motion.constant_velocity());
    wall.move_to(t);
  }

  int bottom_ = -1, top_ = -1;      // wall indices
  double shear_rate_ = 0.0;         // 1/s, U_T / H at the start
  double impulse_ = 0.0;            // N s, into both walls since the last update
  double last_load_ = 0.0;          // N, both walls' load at the last step
  double since_ = 0.0, gap_ = 0.0;  // the last update's time and gap
  long long collisions_ = 0;        // contacts begun between particles at the last update
  long long updates_ = 0;
  CouetteServoState state_;
};

}  // namespace grainflow::dem
