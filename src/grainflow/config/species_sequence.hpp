// The species of each particle a placement routine creates, in a shuffled order so that
// mixtures start mixed (shared by the DEM and event-driven initial states).
#pragma once

#include <algorithm>
#include <random>
#include <vector>

#include "grainflow/config/case_config.hpp"

namespace grainflow {

inline std::vector<int> species_sequence(const CaseConfig& c, std::mt19937_64& rng) {
  std::vector<int> sequence;
  for (std::size_t s = 0; s < c.species.size(); ++s)
    sequence.insert(sequence.end(), static_cast<std::size_t>(c.species[s].count), static_cast<int>(s));
  if (c.species.size() > 1) std::shuffle(sequence.begin(), sequence.end(), rng);
  return sequence;
}

}  // namespace grainflow
