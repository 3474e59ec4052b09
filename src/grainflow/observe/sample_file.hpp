// What every sampled HDF5 file of a soft-sphere run carries, so that it can be read without the
// case, and how such a file is committed with the samples it got.
#pragma once

#include <string>
#include <vector>

#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/observe/run_context.hpp"

namespace grainflow::observe {

void write_run_attributes(io::H5Writer& file, const RunContext& run, double start, const std::string& units);

// Commits a sampled file with the count taken (a shortened record is still valid data) and warns
// when the run ended before all requested samples.
void finish_samples(io::H5Writer& file, const std::string& table, long taken, long requested,
                    std::vector<std::string>& warnings);

}  // namespace grainflow::observe
