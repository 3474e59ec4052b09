// Everything a DEM run holds apart from the contact law: particles, box, walls and their motion,
// clock and step counters. Built from a case by build_dem_state() (initial_state.cpp).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/config/couette_servo_rule.hpp"
#include "grainflow/core/face_wall.hpp"
#include "grainflow/core/periodic_box.hpp"
#include "grainflow/dem/wall_motion.hpp"
#include "grainflow/particles/particle_store.hpp"
#include "grainflow/walls/wall_types.hpp"

namespace grainflow::dem {

// A wall of the soft-sphere engine, a boundary of infinite mass (section 2.6.2): a box face (a plane
// of walls/plane_wall.hpp, `face` >= 0, its FaceWall part what observers read) or a [[geometry]]
// wall of any registered type (`face` = -1, `geometry` its index in the case). Its shape follows a
// rigid motion: the translation of `motion` and a turn at `angular_velocity` about `origin`.
struct DemWall : FaceWall {
  std::string name;   // the face's (xlo ... zhi) or the geometry's
  int geometry = -1;  // index into CaseConfig::geometry, or -1 for a box face
  walls::WallShape initial_shape, shape;  // at t = 0; now
  double base_position = 0.0;  // m, a face's plane coordinate at t = 0
  WallMotion motion;
  Vec3 angular_velocity;        // rad/s about `origin`
  Vec3 initial_origin, origin;  // m, at t = 0; now (moving with the translation)
  Vec3 shift;                   // m, the translation's displacement now
  bool turns = false;     // its turning moves its surface (it does not spin in place): the shape is rotated
  double reach_turn = 0.0;  // m per radian: how far its surface in the box travels as it turns
  double friction = 0.0;  // the contact law's own wall keys are in the case (WallConfig::contact)
  bool bumpy = false;     // backing plane of a bumpy wall

  // Position, velocity and shape at time t (`since` = t: at() is exact only now, as the motion is not linear).
  void move_to(double t) {
    velocity = motion.velocity(t);
    since = t;
    place(t);
  }
  // The shape and origin at time t, from the motion's displacement.
  void place(double t) {
    shift = motion.displacement(t);
    if (face >= 0) position = base_position + shift[axis];
    origin = initial_origin + shift;
    const walls::RigidMotion m{initial_origin, shift,
                               turns ? walls::Rotation::about(angular_velocity, t) : walls::Rotation{}};
    shape = std::visit([&](const auto& s) -> walls::WallShape { return s.moved(m); }, initial_shape);
  }
  // The velocity of the wall's surface at `point`.
  Vec3 surface_velocity(const Vec3& point) const { return velocity + cross(angular_velocity, point - origin); }
  bool spins() const { return angular_velocity != Vec3{}; }
  // How far its surface may have moved between two displacements and times: bounds the particles
  // a wall may reach that were out of its reach when its contact list was built.
  double surface_travel(const Vec3& shift_then, double then, const Vec3& shift_now, double now) const {
    // A turning shape's orientation changed meanwhile: its translation counts whole.
    if (turns) return norm(shift_now - shift_then) + norm(angular_velocity) * std::fabs(now - then) * reach_turn;
    return std::visit([&](const auto& s) { return s.surface_shift(shift_now - shift_then); }, initial_shape);
  }
};

// An outlet: a free particle whose centre lies in the box [lo, hi] leaves the run.
struct OutletRegion {
  Vec3 lo, hi;
  bool holds(const Vec3& x) const {
    return x.x >= lo.x && x.x <= hi.x && x.y >= lo.y && x.y <= hi.y && x.z >= lo.z && x.z <= hi.z;
  }
};

// An insertion: particles of one species put, clear of everything, into the box [lo, hi] (and,
// when `inside` >= 0, inside that wall: clear of its surface on its particles' side): `count` at
// `start`, or `rate` per second from `start` on.
struct InsertionRegion {
  int species = 0;
  double radius = 0.0, mass = 0.0, inv_inertia = 0.0;
  long count = 0;
  double rate = 0.0;
  Vec3 lo, hi, velocity;
  int inside = -1;  // index into DemState::walls
  double start = 0.0;
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
  std::vector<DemWall> walls;  // the box faces first, in face order, then [[geometry]]
  std::array<Vec3, 6> bump_velocity{};      // m/s of the bumps of each face
  std::array<Vec3, 6> bump_displacement{};  // m, displacement applied so far to each face's bumps
  double expansion_rate = 0.0;              // m/s of radius growth (section 2.2), 0 when done
  std::vector<SpeciesConfig> species;
  std::vector<OutletRegion> outlets;  // [[outlet]], in the case's order
  std::vector<int> reinsert;          // per outlet: the insertion its particles go back through, or -1
  std::vector<InsertionRegion> insertions;  // [[insertion]], in the case's order
  bool exchanges = false;             // particles may enter or leave ([[insertion]], [[outlet]])
  CouetteServoRule servo;  // pressure-controlled walls at ylo and yhi, when servo.config.enabled
};

DemState build_dem_state(const CaseConfig& c);

// A free particle of the case's species `species` at `position` with `velocity`, sized and weighed
// as the species (in 2D on the discs' plane, moving in it): what an insertion or the Python module
// puts in. Its id is the engine's to give.
ParticleStore::Record species_particle(const CaseConfig& c, int species, const Vec3& position, const Vec3& velocity);

}  // namespace grainflow::dem
