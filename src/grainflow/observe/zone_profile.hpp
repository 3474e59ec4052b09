// Depth profiles in zones (slabs) along the gravity axis with exact sphere–slab partial-volume
// weighting (Lan 1994, Fig. 3.1): solids fraction, mass-weighted mean velocity and granular
// temperature, long-term averaged over samples. Two temperatures are kept, named distinctly:
//  - temperature_lan: about the instantaneous zone mean u(y,t) (eqs. 3-1-5, 3-1-9),
//  - temperature_time_mean: about the long-term zone mean velocity (Campbell's convention).
// Error bars: samples are summed into contiguous blocks (at most kMaxBlocks; when full, neighbours
// merge and the block length doubles), and each long-term average's standard error comes from
// Flyvbjerg-Petersen blocking of its per-block values (analysis/block_average).
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "grainflow/observe/block_sums.hpp"
#include "grainflow/analysis/partial_volume.hpp"
#include "grainflow/observe/rank_reduce.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

struct ZoneAverages {
  double lo = 0.0, hi = 0.0;  // m, zone bounds along the gravity axis
  double solids_fraction = 0.0;
  Vec3 mean_velocity;                   // m/s
  Vec3 temperature_lan;                 // m^2/s^2 per component
  Vec3 temperature_time_mean;           // m^2/s^2 per component
  double kinetic_energy_density = 0.0;  // J/m^3 of fluctuations about the zone mean (eq. 3-1-10)
  double mass = 0.0;                    // kg, mean over samples
  // Standard errors of the long-term averages (NaN until there are 2 kMinErrorBlocks full blocks).
  double solids_fraction_error = 0.0;
  Vec3 mean_velocity_error;            // m/s
  double temperature_lan_error = 0.0;  // m^2/s^2, of the total (mean of the three components)
  double temperature_time_mean_error = 0.0;
};

class ZoneProfile {
 public:
  // Zones of `thickness` from `lo` up to `hi` (the last one possibly thinner). In 2D zones are
  // strips and the cross-section a length: disc-strip areas weigh the discs, temperatures are per
  // in-plane component.
  ZoneProfile(int axis, double lo, double hi, double thickness, double cross_section_area, int dimension = 3);
  void sample(const ParticleStore& particles);  // one instantaneous sample, accumulated
  std::vector<ZoneAverages> averages() const;
  // Mass-weighted (partial-volume) mean velocity of each zone now, not accumulated; zones without
  // mass read zero. For the zone velocity histories of Lan's spectra (section 4.3).
  std::vector<Vec3> instantaneous_mean_velocity(const ParticleStore& particles);
  std::vector<double> zone_centres() const;  // m, along the axis
  // Along a periodic axis the zones span exactly one period [lo, hi): a sphere straddling the seam
  // counts in the zones at both ends, the share beyond the seam as its image, which moves at
  // `image_velocity` relative to the sphere (Lees-Edwards: shear rate x period along x; else zero).
  void set_period(const Vec3& image_velocity = {}) {
    period_ = hi_ - lo_;
    image_velocity_ = image_velocity;
  }
  // The zone temperature of the whole bed now (timeseries.csv's `zone_temperature`): the
  // mass-weighted mean over zones of each zone's temperature about its instantaneous mean (eq. 3-1-9),
  // sum m |v - u(y,t)|^2 / (D sum m) with partial-volume masses, D = 3 (2 for discs). Not Lan's
  // cell-average temperature, which is about the whole cell's mean velocity (eq. 3-1-2,
  // `cell_temperature`): this one leaves out the zones' collective motion. Not accumulated.
  double instantaneous_temperature(const ParticleStore& particles);
  // Full blocks available for the error bars; below 2 * kMinErrorBlocks the errors read NaN.
  long error_blocks() const { return static_cast<long>(blocks_.blocks().size()); }
  static constexpr std::size_t kMaxBlocks = kMaxErrorBlocks, kMinErrorBlocks = observe::kMinErrorBlocks;
  long samples() const { return samples_; }
  int axis() const { return axis_; }

  // MPI: each rank samples its own particles and `reduce` sums each pass's zone sums over the
  // ranks (in place), so every rank holds the whole box's profile without gathering particles.
  void set_reduce(RankReduce reduce) { reduce_ = std::move(reduce); }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(sums_, samples_, blocks_);
  }

 private:
  struct Sums {
    double mass = 0.0, solid_volume = 0.0;
    Vec3 momentum, second_moment, fluctuation_lan;  // sum m v, sum m v^2, sum m (v - u_inst)^2
    Sums& operator+=(const Sums& o);
  };
  int axis_;
  int dimension_;
  double lo_, hi_, thickness_;       // m; the last zone ends at hi_
  double period_ = 0.0;              // m, hi_ - lo_ along a periodic axis; 0: not periodic
  Vec3 image_velocity_;              // m/s, of the image one period above
  std::vector<double> zone_volume_;  // m^3; the top zone may be cut by the domain's upper bound
  template <class Visit>
  void for_each_overlap(const ParticleStore& p, std::size_t i, Visit&& visit) const;
  template <class Visit>
  void overlap_at(double centre, double radius, double whole, const Vec3& velocity, Visit& visit) const;
  void fill_masses(const ParticleStore& p);
  void fill_fluctuations(const ParticleStore& p);
  void add_errors(std::vector<ZoneAverages>& out) const;

  std::vector<Sums> sums_;
  std::vector<Sums> scratch_, fluctuations_;
  RankReduce reduce_;
  void reduce(std::vector<Sums>& sums) const;
  long samples_ = 0;
  BlockSums<Sums> blocks_;  // for the error bars
};

}  // namespace grainflow::observe
