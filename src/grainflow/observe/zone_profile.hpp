// Depth profiles in zones (slabs) along the gravity axis with exact sphere–slab partial-volume
// weighting (Lan 1994, Fig. 3.1): solids fraction, mass-weighted mean velocity and granular
// temperature, long-term averaged over samples. Two temperatures are kept, named distinctly:
//  - temperature_lan: about the instantaneous zone mean u(y,t) (eqs. 3-1-5, 3-1-9),
//  - temperature_time_mean: about the long-term zone mean velocity (Campbell's convention).
#pragma once

#include <array>
#include <vector>

#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

// Volume of a sphere of radius r centred at c lying between planes a < b.
double sphere_slab_volume(double r, double c, double a, double b);

struct ZoneAverages {
  double lo = 0.0, hi = 0.0;            // m, zone bounds along the gravity axis
  double solids_fraction = 0.0;
  Vec3 mean_velocity;                   // m/s
  Vec3 temperature_lan;                 // m^2/s^2 per component
  Vec3 temperature_time_mean;           // m^2/s^2 per component
  double kinetic_energy_density = 0.0;  // J/m^3 of fluctuations about the zone mean (eq. 3-1-10)
  double mass = 0.0;                    // kg, mean over samples
};

class ZoneProfile {
 public:
  // Zones of `thickness` from `lo` up to `hi` (the last one possibly thinner).
  ZoneProfile(int axis, double lo, double hi, double thickness, double cross_section_area);
  void sample(const ParticleStore& particles);  // one instantaneous sample, accumulated
  std::vector<ZoneAverages> averages() const;
  // Mass-weighted (partial-volume) mean velocity of each zone now, not accumulated; zones without
  // mass read zero. For the zone velocity histories of Lan's spectra (section 4.3).
  std::vector<Vec3> instantaneous_mean_velocity(const ParticleStore& particles);
  std::vector<double> zone_centres() const;  // m, along the axis
  long samples() const { return samples_; }
  int axis() const { return axis_; }

 private:
  struct Sums {
    double mass = 0.0, solid_volume = 0.0;
    Vec3 momentum, second_moment, fluctuation_lan;  // sum m v, sum m v^2, sum m (v - u_inst)^2
  };
  int axis_;
  double lo_, hi_, thickness_;  // m; the last zone ends at hi_
  std::vector<double> zone_volume_;  // m^3; the top zone may be cut by the domain's upper bound
  template <class Visit>
  void for_each_overlap(const ParticleStore& p, std::size_t i, Visit&& visit) const;
  void fill_masses(const ParticleStore& p);

  std::vector<Sums> sums_;
  std::vector<Sums> scratch_;
  long samples_ = 0;
};

}  // namespace grainflow::observe
