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

  template <class Archive>
  void serialize(Archive& ar) {
    std::vector<double> times;
    std::vector<std::string> files;
    for (const auto& [t, f] : entries_) times.push_back(t), files.push_back(f);
    ar(times, files);
    entries_.clear();
    for (std::size_t k = 0; k < times.size() && k < files.size(); ++k) entries_.emplace_back(times[k], files[k]);
  }

 private:
  std::string directory_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace grainflow::io
