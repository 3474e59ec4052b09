// ParaView output: one VTU (unstructured grid of vertices) per snapshot and a PVD index that
// lists them with their simulated times. On several MPI ranks each rank writes its own particles
// as a piece of the snapshot, and rank 0 a parallel index (.pvtu) naming the pieces, which the PVD
// lists: no rank ever holds every particle, and ParaView reads the pieces as one data set.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::io {

// The particles that are not ghosts, as vertices with their diameters, velocities, species and ids.
void write_vtu(const std::string& path, const ParticleStore& particles);
// A parallel index of VTU pieces (file names relative to the index's folder).
void write_pvtu(const std::string& path, const std::vector<std::string>& pieces);

class PvdSeries {
 public:
  // A further data set shown with the particles at every time (a wall): `stem`_<index>.vtp at each
  // snapshot, or `stem`.vtp for one that does not move.
  struct Part {
    std::string stem;
    bool per_snapshot = false;
  };

  explicit PvdSeries(std::string directory) : directory_(std::move(directory)) {}
  // The parts the index lists beside each snapshot's particles (their files are the caller's).
  void set_parts(std::vector<Part> parts) { parts_ = std::move(parts); }
  // The file of `part` at snapshot `index`.
  static std::string part_file(const Part& part, std::size_t index);
  // Writes snapshot `index` at `time` and rewrites the index (atomically) to include it.
  void add(const ParticleStore& particles, double time);
  // MPI: every rank calls this at the same snapshot with its own particles; rank 0 also writes the
  // .pvtu and the index.
  void add_piece(const ParticleStore& particles, double time, int rank, int ranks);
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
  void write_index() const;
  std::string directory_;
  std::vector<std::pair<double, std::string>> entries_;
  std::vector<Part> parts_;
};

}  // namespace grainflow::io
