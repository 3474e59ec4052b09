#include "grainflow/observe/sample_file.hpp"

#include <cstdint>

#include "grainflow/core/version.hpp"

namespace grainflow::observe {

void write_run_attributes(io::H5Writer& file, const RunContext& run, double start, const std::string& units) {
  file.attribute("/", "start", start);
  file.attribute("/", "time_step", run.time_step);
  file.attribute("/", "diameter", run.reference_diameter);
  file.attribute("/", "gravity_axis", static_cast<std::int64_t>(run.gravity_axis));
  file.attribute("/", "case", run.c->path);
  file.attribute("/", "version", std::string(kVersion));
  file.attribute("/", "units", units);
}

void finish_samples(io::H5Writer& file, const std::string& table, long taken, long requested,
                    std::vector<std::string>& warnings) {
  file.attribute("/", "samples", static_cast<std::int64_t>(taken));
  if (taken < requested)
    warnings.push_back(table + ": the run ended after " + std::to_string(taken) + " of the " +
                       std::to_string(requested) + " requested samples (" + table +
                       ".start and samples need a longer run.duration)");
  file.commit();
}

}  // namespace grainflow::observe
