#include "grainflow/observe/bed_surface.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "grainflow/observe/zone_profile.hpp"

namespace grainflow::observe {
namespace {

// Solids fraction in slabs of `thickness` from `floor` up, of the free particles `included` selects.
template <class Include>
std::vector<double> slab_fractions(const ParticleStore& p, int axis, double floor, double area, double thickness,
                                   Include&& included) {
  std::vector<double> volume;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] != Motion::free || !included(i)) continue;
    const double r = p.radius[i], c = p.position[i][axis];
    const int first = std::max(0, static_cast<int>(std::floor((c - r - floor) / thickness)));
    const int last = static_cast<int>(std::floor((c + r - floor) / thickness));
    if (last < 0) continue;
    if (static_cast<int>(volume.size()) <= last) volume.resize(last + 1, 0.0);
    for (int z = first; z <= last; ++z) volume[z] += sphere_slab_volume(r, c, floor + z * thickness, floor + (z + 1) * thickness);
  }
  for (double& v : volume) v /= thickness * area;
  return volume;
}

}  // namespace

BedSurface measure_bed_surface(const ParticleStore& p, int axis, double floor, double area, double diameter,
                               const BedSurfaceThresholds& thresholds) {
  BedSurface out;
  // Ballistic cut: the first dilute zone above the densest one.
  const auto zones = slab_fractions(p, axis, floor, area, diameter, [](std::size_t) { return true; });
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
  const auto slices = slab_fractions(p, axis, floor, area, slice, in_bed);
  std::size_t top = 0;
  for (std::size_t s = 0; s < slices.size(); ++s)
    if (slices[s] >= thresholds.surface_fraction) top = s + 1;
  out.height = top * slice;

  double volume = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.motion[i] != Motion::free) continue;
    if (in_bed(i))
      volume += 4.0 / 3.0 * M_PI * p.radius[i] * p.radius[i] * p.radius[i];
    else
      ++out.ballistic;
  }
  if (out.height > 0.0) out.bulk_solids_fraction = volume / (out.height * area);
  return out;
}

}  // namespace grainflow::observe
