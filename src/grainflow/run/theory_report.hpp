// `grainflow theory CASE|OUTDIR [-o FILE]`: the steady kinetic-theory profiles of a vibrated bed
// (analysis/kinetic_theory.hpp; Lan 1994 section 4.1's comparison with Richman & Martin) for the
// particles, floor and drive of a DEM or event-driven case, as a CSV to overlay on its profiles.csv.
#pragma once

#include <string>
#include <vector>

#include "grainflow/analysis/kinetic_theory.hpp"
#include "grainflow/config/case_config.hpp"

namespace grainflow::run {

struct TheoryOptions {
  std::string input;                       // a case file, or a run's output folder (with summary.json)
  std::string output;                      // default: kinetic_theory.csv here, or OUTDIR/analysis/kinetic_theory.csv
  std::vector<std::string> overrides;      // --set, applied to the case
  std::string contact_value = "torquato";  // torquato | carnahan_starling
};

// What the theory takes from a case, in SI where it has units.
struct TheoryInputs {
  analysis::KineticTheoryParameters parameters;
  double diameter = 0.0, density = 0.0, gravity = 0.0;  // m, kg/m^3, m/s^2
  double boundary_fluctuation_velocity = 0.0;           // V_b (eq. 4-1-3), reported only
  double shaking_acceleration = 0.0;                    // Gamma, reported only
  double floor_amplitude = 0.0;                         // m, along gravity
  double domain_height = 0.0;                           // m, from the floor to the opposite face
  std::vector<std::string> notes;                       // what the theory leaves out of this case
};

// Throws InputError (naming the case file and key) when the case is not a bed over a driven floor
// under gravity that the theory describes.
TheoryInputs theory_inputs(const CaseConfig& c);

// Returns the exit status: 0, or throws InputError (exit 2) / RunError (exit 1, no solution).
int run_theory(const TheoryOptions& options);

}  // namespace grainflow::run
