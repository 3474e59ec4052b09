// A DEM run on several MPI ranks, seen as one: the observers and writers of dem_run.cpp work on a
// whole particle store, so at each sample every rank's own particles (ghosts left out) are
// gathered on rank 0, in id order, together with the rank's clock and walls; the other ranks get
// an empty store. The contact counts are summed and the largest overlap taken over the ranks.
#pragma once

#include "grainflow/core/case_config.hpp"
#include "grainflow/dem/dem_engine.hpp"
#include "grainflow/parallel/communicator.hpp"

namespace grainflow::app {

// Refuses (InputError) what a run of several ranks cannot do yet, before anything is written.
void refuse_beyond_parallel_dem(const CaseConfig& c, bool restarting);

// The slabs for `ranks` ranks over the initial state, with ghosts as far out as a list reaches.
dem::SlabDecomposition dem_slabs(const dem::DemState& initial, int ranks);

// Rank 0: `view` gets every rank's own particles and `local`'s clock and walls.
void gather_view(const dem::DemState& local, const parallel::Communicator& comm, dem::DemState& view);

// A fault seen at an output time on any rank, so that all ranks stop there together and write their
// outputs: "" when none; rank 0 gets the first rank's message, the others a pointer to it.
std::string fault_on_any_rank(const std::string& mine, const parallel::Communicator& comm);

dem::ContactStatistics global_statistics(const dem::ContactStatistics& local, const parallel::Communicator& comm);

}  // namespace grainflow::app
