#include "grainflow/observe/bed_surface.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "grainflow/core/ball_measure.hpp"
#include "grainflow/observe/zone_profile.hpp"

namespace grainflow::observe {
namespace {

// Solids fraction in slabs of `thickness` from `floor` up, of the free particles `included` selects,
// over every rank: the ranks agree on the highest slab first, then add their volumes.
template <class Include>
std::vector<double> slab_fractions(const ParticleStore& p, int dimension, int axis, double floor, double area,
                                   double thickness, const RankReduce& ranks, Include&& included) {
  auto range = [&](std::size_t i) {
    const double r = p.radius[i], c = p.position[i][axis];
    return std::pair{std::max(0, static_cast<int>(std::floor((c - r - floor) / thickness))),
                     static_cast<int>(std::floor((c + r - floor) / thickness))};
  };
  int highest = -1;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.counted(i) && included(i)) highest = std::max(highest, range(i).second);
  std::vector<double> volume(static_cast<std::size_t>(ranks.max(highest) + 1), 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i) || !included(i)) continue;
    const auto [first, last] = range(i);
    const double r = p.radius[i], c = p.position[i][axis];
    for (int z = first; z <= last; ++z)
      volume[z] += particle_slab_measure(dimension, r, c, floor + z * thickness, floor + (z + 1) * thickness);
  }
  ranks.sum(volume.data(), volume.size());
  for (double& v : volume) v /= thickness * area;
  return volume;
}

}  // namespace

BedSurface measure_bed_surface(const ParticleStore& p, int dimension, int axis, double floor, double area,
                               double diameter, const BedSurfaceThresholds& thresholds, const RankReduce& ranks) {
  BedSurface out;
  // Ballistic cut: the first dilute zone above the densest one.
  const auto zones = slab_fractions(p, dimension, axis, floor, area, diameter, ranks, [](std::size_t) { return true; });
  if (zones.empty()) return out;
  const auto densest = std::max_element(zones.begin(), zones.end()) - zones.begin();
  double cut = INFINITY;
  for (std::size_t z = densest; z < zones.size(); ++z)
    if (zones[z] < thresholds.gap_fraction) {
      cut = floor + (z + 0.5) * diameter;
      break;
    }
  auto in_bed = [&](std::size_t i) { return p.position[i][axis] < cut; };

  const double slice = diameter / 10.0;
  const auto slices = slab_fractions(p, dimension, axis, floor, area, slice, ranks, in_bed);
  std::size_t top = 0;
  for (std::size_t s = 0; s < slices.size(); ++s)
    if (slices[s] >= thresholds.surface_fraction) top = s + 1;
  out.height = top * slice;

  double volume_and_ballistic[2] = {};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!p.counted(i)) continue;
    if (in_bed(i)) volume_and_ballistic[0] += ball_measure(dimension, p.radius[i]);
    else volume_and_ballistic[1] += 1.0;
  }
  ranks.sum(volume_and_ballistic, 2);
  out.ballistic = std::lround(volume_and_ballistic[1]);
  if (out.height > 0.0) out.bulk_solids_fraction = volume_and_ballistic[0] / (out.height * area);
  return out;
}

}  // namespace grainflow::observe
