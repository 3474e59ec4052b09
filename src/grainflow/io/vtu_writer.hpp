// ParaView output: one VTU (unstructured grid of vertices) per snapshot and a PVD index that
// lists them with their simulated times.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::io {

void write_vtu(const std::string& path, const ParticleStore& particles);

class PvdSeries {
 public:
  explicit PvdSeries(std::string directory) : directory_(std::move(directory)) {}
  // Writes snapshot `index` at `time` and rewrites the index (atomically) to include it.
  void add(const ParticleStore& particles, double time);
  std::size_t size() const { return entries_.size(); }

 private:
  std::string directory_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace grainflow::io
