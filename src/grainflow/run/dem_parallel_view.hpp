// A DEM run on several MPI ranks, seen as one: the observers run on every rank over its own
// particles and combine their sums through `over_ranks`; the contact counts are summed and the
// largest overlap taken over the ranks. Only final_state.csv and a checkpoint's particle datasets
// need every particle in one place: `gather_particles` brings them to rank 0, in id order.
#pragma once

#include "grainflow/config/case_config.hpp"
#include "grainflow/dem/dem_engine.hpp"
#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/parallel/communicator.hpp"

namespace grainflow::run {

// Sums and maxima over the ranks for the observers (the identity on one rank).
observe::RankReduce over_ranks(const parallel::Communicator& comm);

// The grid of sub-domains for `ranks` ranks over the initial state, with ghosts as far out as a
// neighbour list reaches.
dem::DomainDecomposition dem_grid(const dem::DemState& initial, int ranks);

// Rank 0: every rank's own particles in id order, with the fields final_state.csv and a
// checkpoint's datasets read (position, velocity, spin, radii, species, id, motion; the store's
// other arrays stay empty). The other ranks get an empty store.
ParticleStore gather_particles(const ParticleStore& local, const parallel::Communicator& comm);

// A fault seen at an output time on any rank, so that all ranks stop there together and write their
// outputs: "" when none; rank 0 gets the first rank's message, the others a pointer to it.
std::string fault_on_any_rank(const std::string& mine, const parallel::Communicator& comm);

dem::ContactStatistics global_statistics(const dem::ContactStatistics& local, const parallel::Communicator& comm);

}  // namespace grainflow::run
