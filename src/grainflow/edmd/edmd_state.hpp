// Everything an event-driven run holds apart from its scheduling structures: particles, box,
// gravity, walls and collision rules. While events run the engine keeps positions and velocities
// in its own per-particle records (each on its own clock); the particle store is brought up to
// date whenever the engine synchronizes (at the end of every advance_to).
#pragma once

#include <vector>

#include "grainflow/config/case_config.hpp"
#include "grainflow/core/face_wall.hpp"
#include "grainflow/core/periodic_box.hpp"
#include "grainflow/edmd/collision_rules.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::edmd {

// A plane wall on one face of the box, moving at constant velocity (Couette walls slide along
// the flow direction; the pressure servo changes the normal speed between events).
struct EdmdWall : FaceWall {
  WallCondition condition = WallCondition::smooth;
  RestitutionLaw restitution;
};

struct EdmdState {
  int dimension = 3;
  ParticleStore particles;  // positions and velocities valid at `time` after a synchronize
  PeriodicBox box;
  Vec3 gravity;       // m/s^2
  double time = 0.0;  // s
  std::vector<EdmdWall> walls;
  RestitutionLaw restitution;  // particle-particle
  double tangential_restitution = -1.0;
  double rolling_speed = 0.0;  // m/s, wall rebounds slower than this roll (Campbell section 2.14.2)
  double contact_duration =
      0.0;  // s, TC model (Luding & McNamara): elastic within this time of a particle's last collision
  double separation_gap = 0.0;  // Campbell's re-separation after each collision, relative to the contact distance
  std::vector<SpeciesConfig> species;
  ServoConfig servo;               // pressure-controlled Couette walls, when enabled
  double lees_edwards_rate = 0.0;  // 1/s, shear rate of Lees–Edwards boundaries (flow x, gradient y)
  double stress_unit = 1.0;        // m U_T^2 / R^2 (2D) or / R^3 (3D): Campbell's stress scale for the servo
  double speed_unit = 1.0;         // m/s, U_T at the start
};

EdmdState build_edmd_state(const CaseConfig& c);

}  // namespace grainflow::edmd
