// What a DEM run writes of its [[geometry]] walls besides the particles: their loads for the
// observers (geometry.csv) and their surfaces beside each snapshot (snapshots/<name>[_index].vtp,
// listed in particles.pvd as further parts).
#pragma once

#include <string>
#include <vector>

#include "grainflow/dem/dem_state.hpp"
#include "grainflow/io/vtu_writer.hpp"
#include "grainflow/observe/observer.hpp"

namespace grainflow::run {

// Each geometry wall's load at the engine's last force evaluation (this rank's share), in case order.
template <class E>
std::vector<observe::GeometryLoad> geometry_loads(const E& e) {
  std::vector<observe::GeometryLoad> loads;
  const std::vector<dem::DemWall>& walls = e.state().walls;
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (walls[w].geometry >= 0) loads.push_back({walls[w].name, e.force_on_wall(w), e.torque_on_wall(w)});
  return loads;
}

// What each [[outlet]] has removed so far (this rank's particles), in case order.
template <class E>
std::vector<observe::OutletTally> outlet_tallies(const E& e) {
  std::vector<observe::OutletTally> tallies;
  for (const auto& count : e.outlet_counts()) tallies.push_back({count.removed, count.mass});
  return tallies;
}

// A wall whose surface moves (it turns off its own axis or translates) is drawn at every snapshot;
// one that stands still or spins in place once.
class WallSnapshots {
 public:
  WallSnapshots(std::string directory, const std::vector<dem::DemWall>& walls);
  // The parts particles.pvd lists beside the particles, one per geometry wall.
  const std::vector<io::PvdSeries::Part>& parts() const { return parts_; }
  // Draws the walls of snapshot `index` (rank 0), before the index names them.
  void write(const std::vector<dem::DemWall>& walls, const PeriodicBox& box, std::size_t index);

 private:
  std::string directory_;
  std::vector<io::PvdSeries::Part> parts_;
  bool still_written_ = false;  // the walls that do not move, once per process
};

}  // namespace grainflow::run
