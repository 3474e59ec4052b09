// Whole-system quantities at one instant: kinetic energies, granular temperature (fluctuation
// about the mass-mean velocity) and the mass-centre height along the gravity axis.
#pragma once

#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

struct GlobalSample {
  double kinetic_energy = 0.0;        // J, translational, moving particles
  double rotational_energy = 0.0;     // J
  double granular_temperature = 0.0;  // m^2/s^2, (1/3) <|v - <v>|^2>, mass weighted
  Vec3 component_temperature;         // m^2/s^2, <(v_a - <v_a>)^2> per axis (Lan's T_x, T_y, T_z), mass weighted
  double mass_center_height = 0.0;    // m, along the gravity axis
  Vec3 momentum;                      // kg m/s
  double mass = 0.0;                  // kg of moving particles
};

// Over the moving particles this rank owns (ghosts left out), summed over the ranks by `ranks`.
// The granular temperature is per degree of freedom of the `dimension` translations.
GlobalSample sample_global(const ParticleStore& particles, int gravity_axis, int dimension,
                           const RankReduce& ranks = {});

}  // namespace grainflow::observe
