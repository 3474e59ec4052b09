// Campbell's strip profiles of a shear flow (Campbell 1982 sections 2.15, 3.1-3.2, Fig. 2.11):
// particles count in the strips of a StripGrid with the exact share of their area (discs) or
// volume (spheres) lying in each, and every sample adds to long-term sums per strip index (the
// strips of a Couette cell stretch with its walls; strip k stays strip k). From the sums:
//  - solids fraction nu, mass-weighted mean velocity <u> and angular velocity <omega>;
//  - Campbell's fluctuations about the *time-mean* strip velocity (section 3.1.1):
//    <u'^2> = <u^2> - <u>^2, <v'^2>, <w'^2>, the cross moment <u'v'> = <uv> - <u><v>, and the
//    rotational one beta <omega'^2> with beta = I/m (per rotational degree of freedom);
//  - Campbell's "temperature" 1/2 m (<u'^2> + <v'^2> + beta <omega'^2>) and "translational
//    temperature" 1/2 m (<u'^2> + <v'^2>), energies per particle (3D: with w and all spins);
//  - the granular temperature per translational degree of freedom, sum_i <u_i'^2> / D;
//  - Lan's temperature about the *instantaneous* strip mean, per translational degree of freedom.
// Every average has a block-averaged standard error (observe/block_sums.hpp).
#pragma once

#include <array>
#include <vector>

#include "grainflow/core/vec3.hpp"
#include "grainflow/observe/block_sums.hpp"
#include "grainflow/analysis/strip_grid.hpp"
#include "grainflow/particles/particle_store.hpp"

namespace grainflow::observe {

// Packing limits of sheared discs (Campbell 1982 section 3.1.7), for plots and the plug-flow flag.
inline constexpr double kDiscTriangularPacking = 0.9068996821171089;  // pi / (2 sqrt 3): cannot shear
inline constexpr double kDiscContourShearPacking =
    0.8210210538742287;  // pi / (sqrt 3 + 2 pi / 3): layers riding over each other
inline constexpr double kDiscSquarePacking = 0.7853981633974483;  // pi / 4: layers slide freely
// The spheres' counterpart of pi/4 by Campbell's spacing correspondence nu_3D = 4/(3 sqrt pi) nu^(3/2)
// (section 3.1): pi / 6, the simple cubic packing, whose layers also slide over each other.
inline constexpr double kSphereCubicPacking = 0.5235987755982988;

// The long-term averages of one strip; value[q] and error[q] for each quantity q.
namespace strip {
enum Quantity : int {
  solids_fraction,
  mass,       // kg, mean per sample
  particles,  // mean number per sample (counted by share)
  u,
  v,
  w,  // m/s, mass-weighted mean velocity
  omega_x,
  omega_y,
  omega_z,  // rad/s, mass-weighted mean angular velocity
  u_variance,
  v_variance,
  w_variance,                 // m^2/s^2, <u'^2>, <v'^2>, <w'^2> about the time mean
  uv_covariance,              // m^2/s^2, <u'v'>
  rotational_temperature,     // m^2/s^2, beta <|omega'|^2> per rotational degree of freedom
  granular_temperature,       // m^2/s^2, (<u'^2> + <v'^2> [+ <w'^2>]) / D
  temperature,                // J per particle, Campbell's 1/2 m (sum <u_i'^2> + beta <|omega'|^2>)
  translational_temperature,  // J per particle, 1/2 m sum <u_i'^2>
  temperature_lan,            // m^2/s^2 per translational degree of freedom, about the instantaneous mean
  kQuantities
};
}  // namespace strip

struct StripAverages {
  double centre = 0.0;           // m, mean over the samples (a stretching strip moves)
  double relative_centre = 0.0;  // (k + 1/2) / count: the centre as a fraction of the strips' span
  std::array<double, strip::kQuantities> value{}, error{};  // velocity-type values NaN without mass
  bool has_mass() const { return value[strip::mass] > 0.0; }
};

class StripProfile {
 public:
  StripProfile(int dimension, int count);
  // One instantaneous sample of every free particle, in the strips of `grid` (the grid of the
  // moment; its count must be this profile's).
  void sample(const ParticleStore& particles, const StripGrid& grid);
  std::vector<StripAverages> averages() const;
  long samples() const { return samples_; }

  template <class Archive>
  void serialize(Archive& ar) {
    ar(sums_, samples_, blocks_);
  }
  int count() const { return static_cast<int>(sums_.size()); }
  int dimension() const { return dimension_; }

 private:
  struct Sums {
    double solids_fraction = 0.0;  // solid measure / strip measure, summed over samples
    double centre = 0.0;           // m
    double mass = 0.0, particles = 0.0, inertia = 0.0;
    Vec3 momentum, second_moment;  // sum m v, sum m v_i^2 (per component)
    double cross = 0.0;            // sum m v_x v_y
    Vec3 mass_spin, inertia_spin;  // sum m omega, sum I omega
    double spin_second = 0.0;      // sum I |omega|^2
    double fluctuation_lan = 0.0;  // sum m |v - u(t)|^2 over the translational components
    long samples = 0;
    Sums& operator+=(const Sums& o);
  };
  std::array<double, strip::kQuantities> values_of(const Sums& s) const;

  int dimension_;
  std::vector<Sums> sums_, scratch_;
  long samples_ = 0;
  BlockSums<Sums> blocks_;
};

}  // namespace grainflow::observe
