// How many particles and walls a particle touches (coordination numbers, Lan 1994 Fig. A5.17).
#pragma once

namespace grainflow::engine_api {

struct Coordination {
  int particles = 0, walls = 0;
};

}  // namespace grainflow::engine_api
