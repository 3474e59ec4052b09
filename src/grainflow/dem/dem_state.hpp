// Everything a DEM run holds apart from the contact law: particles, box, walls and their motion,
// clock and step counters. Built from a case by build_dem_state() (initial_state.cpp).
#pragma once

#include <array>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/config/couette_servo_rule.hpp"
#include "grainflow/core/face_wall.hpp"
#include "grainflow/core/periodic_box.hpp"
#include "grainflow/dem/wall_motion.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::dem {

// A flat wall on one face of the box: a boundary sphere of infinite mass (section 2.6.2).
struct FlatWall : FaceWall {
  double base_position = 0.0;  // m, plane coordinate at t = 0
  WallMotion motion;
  double friction = 0.0;  // the contact law's own wall keys are in the case (WallConfig::contact)
  bool bumpy = false;     // backing plane of a bumpy wall

  // Position and velocity at time t (`since` = t: at() is exact only now, as the motion is not linear).
  void move_to(double t) {
    position = base_position + motion.displacement(t)[axis];
    velocity = motion.velocity(t);
    since = t;
  }
};

struct DemState {
  // 2: discs in the x-y plane at the box's mid-z, masses per unit thickness. Nothing then moves them
  // off it: every contact normal, tangential force and gravity lies in the plane and every torque
  // along z, exactly, so the engine runs the same code as in 3D. The box is not periodic along z.
  int dimension = 3;
  ParticleStore particles;
  PeriodicBox box;
  Vec3 gravity;            // m/s^2
  double time = 0.0;       // s
  double time_step = 0.0;  // s
  long step = 0;
  double skin = 0.0;            // m
  double cohesion_reach = 0.0;  // m: how far apart an adhesive contact's surfaces may be pulled before it breaks
  std::vector<FlatWall> walls;
  std::array<Vec3, 6> bump_velocity{};      // m/s of the bumps of each face
  std::array<Vec3, 6> bump_displacement{};  // m, displacement applied so far to each face's bumps
  double expansion_rate = 0.0;              // m/s of radius growth (section 2.2), 0 when done
  std::vector<SpeciesConfig> species;
  CouetteServoRule servo;  // pressure-controlled walls at ylo and yhi, when servo.config.enabled
};

DemState build_dem_state(const CaseConfig& c);

}  // namespace grainflow::dem
