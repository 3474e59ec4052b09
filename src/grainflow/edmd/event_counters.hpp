// What an event-driven run counts as it goes, and the Couette servo's last measurement.
#pragma once

#include "grainflow/config/couette_servo_rule.hpp"

namespace grainflow::edmd {

struct EventCounters {
  long long events = 0;      // every processed event, stale ones included
  long long collisions = 0;  // particle-particle
  long long wall_collisions = 0;
  long long cell_crossings = 0;
  long long stale = 0;           // events found invalid and re-predicted
  long long list_rebuilds = 0;   // neighbour-list rebuilds (the list path has these instead of cell crossings)
  long long rolling_starts = 0;  // wall rebounds too slow to bounce: the particle rolls
  double virial = 0.0;           // sum over collisions of r_ij . J_i (kg m^2/s), for the pressure
  double dissipated = 0.0;       // J lost in collisions (and in the last impact of a particle starting to roll)
  // The energy budget (engine_api/energy_budget.hpp): work done on the particles by moving walls and
  // by images that move (Lees-Edwards rows, a Couette cell's width), J since the start; gravity's
  // work along x carried by Lees-Edwards shifts (the unwrapped x jumps by the row offset); and the
  // energies at the start the changes are measured from.
  double wall_work = 0.0;
  double boundary_work = 0.0;
  double gravity_shift_work = 0.0;
  double separation_work = 0.0;           // J, potential energy the re-separation shifts gave
  double start_energy = 0.0;              // J, kinetic + rotational + bounded potential
  double start_periodic_potential = 0.0;  // J
  long long servo_updates = 0;            // pressure-servo wall speed changes
  long long tc_collisions = 0;            // particle-particle collisions the TC model made elastic and smooth
  long long tc_wall_collisions = 0;
};

// The pressure-controlled Couette cell as last measured (section 2.14.3).
using ServoState = CouetteServoState;

}  // namespace grainflow::edmd
