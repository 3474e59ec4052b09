// Pair distributions of Campbell 1982 section 3.4.3: the number density of particles at a given
// distance from a test particle, p(r | r0). Test particles: those whose centre lies within one
// diameter of the midplane between the walls (every particle when y is periodic). Distances
// [0, range) (Campbell: 8R) fall into equal slices.
//  - normal: every other particle, by |dy| (the distance across the flow, any x).
//  - parallel: particles whose |dy| is under one diameter (the test particle's layer; in 3D also
//    |dz| under a diameter: a tube along the streamline), by the forward periodic distance along
//    the flow, (x_j - x_i) mod W, as Campbell counted (his peak near 8R is the periodic image of the
//    2R peak in a cell about 10R wide).
//  - parallel_two_sided: the same particles by the nearest-image |dx| (at most W/2).
// Each count is divided by the measure (area in 2D, volume in 3D) of the region its slice covers,
// summed over test particles and samples, so that particles placed uniformly at random give the
// number density n at every distance. Regions are clipped to the cell between the walls (and to the
// periodic lengths), so a slice reaching past a wall is normalised by what lies inside; a slice
// with no measure (beyond W, or beyond W/2 for the two-sided distribution) is NaN.
// The errors are those of a ratio estimator, density = sum of counts / sum of measures over the
// samples: the series c_t - density m_t (over the mean measure) is block-averaged.
#pragma once

#include <cstddef>
#include <vector>

#include "grainflow/analysis/state_samples.hpp"

namespace grainflow::analysis {

struct PairDistributionOptions {
  double range = 0.0;  // m; 0: four mean diameters (8R)
  int slices = 50;
};

struct PairDistributions {
  std::vector<double> r;                                     // m, slice centres
  std::vector<double> normal, parallel, parallel_two_sided;  // 1/m^2 (2D) or 1/m^3 (3D)
  // Standard errors from the scatter of the samples: each sample's count less the density times
  // its measure, block-averaged (Flyvbjerg-Petersen) over the sample sequence, so that correlated
  // successive samples and test particles sharing partners are accounted for. NaN with < 2 samples.
  std::vector<double> normal_error, parallel_error, parallel_two_sided_error;
  double slice = 0.0;                // m, slice width
  double number_density = 0.0;       // the cell's: particles / (gap x width (x depth)), mean over samples
  double band_number_density = 0.0;  // test-particle centres / the test band's measure, mean over samples
  double test_particles_per_sample = 0.0;
  double diameter = 0.0;  // m, mean
};

PairDistributions pair_distributions(const StateSamples& s, const PairDistributionOptions& options);

// Length of the part of [a, b) inside [lo, hi).
inline double overlap_length(double a, double b, double lo, double hi) {
  const double l = (b < hi ? b : hi) - (a > lo ? a : lo);
  return l > 0.0 ? l : 0.0;
}

}  // namespace grainflow::analysis
