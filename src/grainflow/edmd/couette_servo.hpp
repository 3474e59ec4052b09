// Campbell's pressure-controlled Couette cell (section 2.14.3, listing COL002): the walls at ylo and
// yhi move apart or together so that the normal stress they measure approaches its target, the top
// wall's speed keeps the shear rate U_T / H, and the periodic width follows the gap (the aspect ratio
// stays fixed). A system acting on the event-driven engine: the engine hands it each wall
// collision's normal impulse and asks whether an update is due; the servo sets the walls' motion and
// the width law L(t); the engine brings its particles and cell grid along.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include "grainflow/config/couette_servo_rule.hpp"
#include "grainflow/edmd/edmd_state.hpp"
#include "grainflow/edmd/event_counters.hpp"

namespace grainflow::edmd {

class CouetteServo {
 public:
  CouetteServo() = default;
  // Sized for the state's walls; with [servo], takes the two walls and the start's aspect ratio and
  // shear rate. Without, the width stays the box's (width_rate() = 0).
  explicit CouetteServo(const EdmdState& s) : width_ref_(s.box.length(0)), width_since_(s.time) {
    wall_normal_impulse_.assign(s.walls.size(), 0.0);
    if (!s.servo.enabled) return;
    bottom_wall_ = wall_with_role(s.walls, WallRole::shear_bottom);
    top_wall_ = wall_with_role(s.walls, WallRole::shear_top);
    const double gap = gap_at(s, s.time);
    aspect_ = s.box.length(0) / gap;
    shear_rate_ = (s.walls[top_wall_].velocity.x - s.walls[bottom_wall_].velocity.x) / gap;
    since_ = s.time;
    gap_ = gap;
    state_.gap = gap;
    state_.width = s.box.length(0);
    state_.top_speed = s.walls[top_wall_].velocity.x;
  }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(width_ref_, width_rate_, width_since_, wall_normal_impulse_, since_, gap_, collisions_, state_);
  }

  // The periodic width L(t) = L_ref + L' (t - t_ref); L' = 0 but while the width follows the gap.
  double width_at(double t) const { return width_ref_ + width_rate_ * (t - width_since_); }
  double width_rate() const { return width_rate_; }
  double gap_at(const EdmdState& s, double t) const { return s.walls[top_wall_].at(t) - s.walls[bottom_wall_].at(t); }
  const ServoState& state() const { return state_; }

  void add_normal_impulse(int wall, double impulse) { wall_normal_impulse_[wall] += impulse; }

  // After every servo.every_collisions collisions, once the gap has changed by servo.gap_change, or
  // at the first event once servo.interval has passed.
  bool due(const EdmdState& s, long long collisions) const {
    return collisions - collisions_ >= s.servo.every_collisions ||
           std::fabs(gap_at(s, s.time) - gap_) >= s.servo.gap_change ||
           (s.servo.interval > 0.0 && s.time - since_ >= s.servo.interval);
  }

  // Listing COL002: v <- v/2 + (sigma_measured - sigma_target), in Campbell's units (U_T for speeds,
  // m U_T^2 / R^2 for 2D stresses), clipped to +-sigma_target. False when no time has passed since
  // the last update (nothing to measure).
  bool measure(const EdmdState& s, int dim) {
    const double span = s.time - since_;
    if (span <= 0.0) return false;
    double area = s.box.length(0);
    if (dim == 3) area *= s.box.length(2);
    stress_ = 0.5 * (wall_normal_impulse_[bottom_wall_] + wall_normal_impulse_[top_wall_]) / (span * area);
    speed_ = rule(s).wall_speed(state_.wall_speed, stress_);
    return true;
  }

  // Both walls move at the measured speed from now (particles are current); their speeds along x
  // keep the shear rate; the width law restarts from now. True when the width now changes (the engine's
  // cell grid must follow).
  bool move_walls(EdmdState& s) {
    const double now = s.time;
    new_gap_ = gap_at(s, now);
    for (int w : {bottom_wall_, top_wall_}) {
      EdmdWall& wall = s.walls[w];
      wall.position = wall.at(now);
      wall.since = now;
      wall.velocity.y = w == bottom_wall_ ? -speed_ : speed_;
    }
    if (s.servo.keep_shear_rate) keep_shear_rate(s);
    if (!s.servo.scale_width) return false;
    width_ref_ = width_at(now);
    width_since_ = now;
    width_rate_ = aspect_ * 2.0 * speed_;
    return true;
  }

  // U_T = shear rate x gap. Campbell's listing resets the top wall's speed alone; each reset is a
  // jump in the top wall's speed that heats the top side only. With "both" the walls' speeds change
  // by half the jump each, in opposite senses, and the walls' mean velocity stays.
  void keep_shear_rate(EdmdState& s) const {
    rule(s).keep_shear_rate(s.walls[bottom_wall_].velocity.x, s.walls[top_wall_].velocity.x, shear_rate_ * new_gap_);
  }

  // The update's record, once the box has its new width; impulses count afresh from here.
  void finish_update(const EdmdState& s, long long collisions) {
    state_ = {new_gap_, s.box.length(0), speed_, stress_, s.walls[top_wall_].velocity.x};
    std::fill(wall_normal_impulse_.begin(), wall_normal_impulse_.end(), 0.0);
    since_ = s.time;
    gap_ = new_gap_;
    collisions_ = collisions;
  }

  // The gap and width at time t, between updates (the outputs read them).
  void observe(const EdmdState& s, double t) {
    state_.gap = gap_at(s, t);
    state_.width = s.box.length(0);
  }

 private:
  static CouetteServoRule rule(const EdmdState& s) { return {s.servo, s.speed_unit, s.stress_unit}; }

  double width_ref_ = 0.0, width_rate_ = 0.0, width_since_ = 0.0;  // the periodic width L(t)
  std::vector<double> wall_normal_impulse_;                        // kg m/s into each wall since the last update
  int bottom_wall_ = -1, top_wall_ = -1;
  double aspect_ = 0.0, shear_rate_ = 0.0;             // at the start: width / gap, U_T / H
  double since_ = 0.0, gap_ = 0.0;                     // the last update's time and gap
  long long collisions_ = 0;                           // particle collisions at the last update
  double stress_ = 0.0, speed_ = 0.0, new_gap_ = 0.0;  // the update under way
  ServoState state_;
};

}  // namespace grainflow::edmd
