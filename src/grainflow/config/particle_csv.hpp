// Reads explicit initial particles from CSV: a header row naming the columns species,x,y,z,vx,vy,vz
// (required) and wx,wy,wz,diameter,id (optional; id is ignored); lines starting with '#' are comments.
#pragma once

#include <istream>
#include <string>
#include <vector>

#include "grainflow/config/case_config.hpp"

namespace grainflow::io {

// Throws InputError(path, "line N", reason) on malformed input, or when `path` is not a regular
// file (a device such as /dev/zero would never end).
std::vector<InitialParticle> read_particle_csv(const std::string& path);
// The same from a stream; `path` names it in the messages.
std::vector<InitialParticle> read_particle_csv(std::istream& in, const std::string& path);

}  // namespace grainflow::io
