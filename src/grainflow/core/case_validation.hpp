// Physical and geometric checks on a parsed case that need more than one key: things that fit,
// time steps that resolve contacts, bumpy walls that hold particles. Throws InputError.
#pragma once

#include "grainflow/core/case_config.hpp"

namespace grainflow {

void validate_case(const CaseConfig& c);

// Largest centre-to-centre spacing of a bumpy lattice that stops a free sphere of `free_radius`
// passing between bumps of `bump_radius` (section 2.6.3): the hole's centre is s/sqrt(2) (square)
// or s/sqrt(3) (triangular) from the nearest bumps.
double max_bump_spacing(const std::string& lattice, double bump_radius, double free_radius);

}  // namespace grainflow
