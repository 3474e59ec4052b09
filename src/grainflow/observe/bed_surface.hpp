// Bed height and bulk solids fraction of a vibrated bed at one instant, as Lan (1994, section 4.2)
// measured them for the comparison with Hunt et al.'s paper-lid heights: particles in ballistic
// flight above the bed are removed, the height is read off the remaining solids-fraction profile,
// and bulk nu = volume of the remaining spheres / (height x cross-section).
// The two thresholds Lan did not state, defined here:
//  - gap_fraction: scanning up from the densest zone (zones one diameter thick), the first zone
//    whose solids fraction is below this ends the bed; particles centred above that zone's middle
//    are ballistic. A paper lid resting on the bed is not lifted by grains flying over a gap.
//  - surface_fraction: the bed surface is the top of the highest thin slice (d / 10) in which the
//    remaining particles fill at least this solids fraction; for a full top layer that is within
//    0.07 r of the tops of its spheres, where the lid would rest.
#pragma once

#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

struct BedSurfaceThresholds {
  double gap_fraction = 0.05;
  double surface_fraction = 0.1;
};

struct BedSurface {
  double height = 0.0;                // m, surface above the floor
  double bulk_solids_fraction = 0.0;  // volume of non-ballistic spheres / (height * area)
  long ballistic = 0;                 // particles excluded as in ballistic flight
};

// `floor` is the floor's position along `axis` (gravity along -axis); `area` the cross-section
// normal to it; `diameter` sets the zone (d) and slice (d / 10) thicknesses. Over the particles
// this rank owns, the profiles and counts summed over the ranks by `ranks`.
// In 2D (discs) `area` is the floor's length and the solids fractions are area fractions.
BedSurface measure_bed_surface(const ParticleStore& particles, int dimension, int axis, double floor, double area,
                               double diameter, const BedSurfaceThresholds& thresholds, const RankReduce& ranks = {});

}  // namespace grainflow::observe
