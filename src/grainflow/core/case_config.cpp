#include "grainflow/core/case_config.hpp"

#include <cmath>

namespace grainflow {

double SpeciesConfig::mass() const { return M_PI / 6.0 * diameter * diameter * diameter * density; }

}  // namespace grainflow
