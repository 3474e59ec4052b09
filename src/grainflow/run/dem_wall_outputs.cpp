#include "grainflow/run/dem_wall_outputs.hpp"

#include <filesystem>

#include "grainflow/io/vtp_writer.hpp"

namespace grainflow::run {

WallSnapshots::WallSnapshots(std::string directory, const std::vector<dem::DemWall>& walls)
    : directory_(std::move(directory)) {
  for (const dem::DemWall& w : walls)
    if (w.geometry >= 0) parts_.push_back({w.name, w.turns || w.motion.moves()});
}

void WallSnapshots::write(const std::vector<dem::DemWall>& walls, const PeriodicBox& box, std::size_t index) {
  std::filesystem::create_directories(directory_);
  std::size_t part = 0;
  for (const dem::DemWall& w : walls) {
    if (w.geometry < 0) continue;
    const io::PvdSeries::Part& p = parts_[part++];
    if (!p.per_snapshot && still_written_) continue;
    const walls::SurfaceMesh mesh = std::visit([&](const auto& s) { return s.mesh(box.lo, box.hi); }, w.shape);
    io::write_vtp(directory_ + "/" + io::PvdSeries::part_file(p, index), mesh.points, mesh.triangles);
  }
  still_written_ = true;
}

}  // namespace grainflow::run
