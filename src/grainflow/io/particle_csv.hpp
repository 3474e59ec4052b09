// Reads explicit initial particles from CSV: a header row naming the columns species,x,y,z,vx,vy,vz
// (required) and wx,wy,wz,diameter,id (optional; id is ignored); lines starting with '#' are comments.
#pragma once

#include <string>
#include <vector>

#include "grainflow/core/case_config.hpp"

namespace grainflow::io {

// Throws InputError(path, "line N", reason) on malformed input.
std::vector<InitialParticle> read_particle_csv(const std::string& path);

}  // namespace grainflow::io
