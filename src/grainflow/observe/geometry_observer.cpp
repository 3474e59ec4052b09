#include "grainflow/observe/geometry_observer.hpp"

#include <algorithm>
#include <iomanip>
#include <iterator>

#include "grainflow/io/atomic_file.hpp"

namespace grainflow::observe {

GeometryObserver::GeometryObserver(const RunContext& run)
    : ranks_(run.ranks), schedule_(run.c->output.interval, run.time_step) {
  for (const GeometryConfig& g : run.c->geometry) names_.push_back(g.name);
}

void GeometryObserver::take(const Frame& now) {
  if (!now.geometry_loads) return;
  const std::vector<GeometryLoad> loads = now.geometry_loads();
  std::vector<double> row(6 * names_.size(), 0.0);
  for (std::size_t g = 0; g < loads.size() && g < names_.size(); ++g) {
    const GeometryLoad& l = loads[g];
    const double six[] = {l.force.x, l.force.y, l.force.z, l.torque.x, l.torque.y, l.torque.z};
    std::copy(std::begin(six), std::end(six), row.begin() + 6 * g);
  }
  ranks_.sum(row.data(), row.size());  // each rank's particles' share
  values_.push_back(now.time);
  values_.insert(values_.end(), row.begin(), row.end());
}

void GeometryObserver::write_file(const OutputSink& out) const {
  if (!out.writes || names_.empty()) return;
  const std::size_t width = 1 + 6 * names_.size();
  io::write_atomically(out.directory + "/geometry.csv", [&](std::ostream& file) {
    file << "# units: time s, force N, torque N m (about the geometry's [geometry.motion] origin, moving with it); "
            "what the particles exert on each [[geometry]] wall at the last force evaluation\n";
    file << "time,name,force_x,force_y,force_z,torque_x,torque_y,torque_z\n";
    file << std::setprecision(10);
    for (std::size_t s = 0; s + width <= values_.size(); s += width)
      for (std::size_t g = 0; g < names_.size(); ++g) {
        file << values_[s] << ',' << names_[g];
        for (int k = 0; k < 6; ++k) file << ',' << values_[s + 1 + 6 * g + k] + 0.0;  // no -0
        file << '\n';
      }
  });
}

}  // namespace grainflow::observe
