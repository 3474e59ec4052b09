// Zone profiles (Lan 1994 Fig. 3.1, eqs. 3-1-5, 3-1-9): exact sphere-slab partial volumes, solids
// fraction of known packings, mass-weighted mean velocity, and the two granular temperatures:
// about the instantaneous zone mean (Lan) and about the long-term zone mean (Campbell).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "grainflow/observe/zone_profile.hpp"

using namespace grainflow;
using namespace grainflow::observe;

namespace {

double sphere_volume(double r) { return 4.0 / 3.0 * M_PI * r * r * r; }
// Spherical cap of height h (0 <= h <= 2r): pi h^2 (3r - h) / 3.
double cap_volume(double r, double h) { return M_PI * h * h * (3.0 * r - h) / 3.0; }

void add(ParticleStore& p, Vec3 x, double r, double density, Vec3 v, Motion motion = Motion::free) {
  const std::size_t i = p.size();
  p.resize(i + 1);
  p.position[i] = x;
  p.radius[i] = p.target_radius[i] = r;
  p.mass[i] = density * sphere_volume(r);
  p.inv_mass[i] = motion == Motion::free ? 1.0 / p.mass[i] : 0.0;
  p.velocity[i] = v;
  p.id[i] = static_cast<std::uint32_t>(i);
  p.motion[i] = motion;
}

}  // namespace

TEST(SphereSlabVolume, SlabsPartitioningTheSphereSumToItsVolume) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double r = 0.001 + 0.01 * u(rng), c = -0.05 + 0.1 * u(rng);
    const double thickness = (0.05 + 3.0 * u(rng)) * r, lo = c - r - thickness * (0.01 + 2.0 * u(rng));
    double sum = 0.0;
    for (double a = lo; a < c + r + thickness; a += thickness) sum += sphere_slab_volume(r, c, a, a + thickness);
    EXPECT_NEAR(sum, sphere_volume(r), 1e-12 * sphere_volume(r)) << "r = " << r << " slab " << thickness;
  }
}

TEST(SphereSlabVolume, MatchesSphericalCaps) {
  const double r = 0.003, c = 0.1;
  for (double h : {0.0, 1e-5, 0.0007, 0.003, 0.0041, 0.006}) {
    // Cap at the top: the slab [c + r - h, far above].
    EXPECT_NEAR(sphere_slab_volume(r, c, c + r - h, c + 1.0), cap_volume(r, h), 1e-15 + 1e-12 * cap_volume(r, h)) << h;
    // Cap at the bottom: the slab [far below, c - r + h].
    EXPECT_NEAR(sphere_slab_volume(r, c, c - 1.0, c - r + h), cap_volume(r, h), 1e-15 + 1e-12 * cap_volume(r, h)) << h;
  }
  // A slab of the sphere's middle: sphere minus two caps.
  EXPECT_NEAR(sphere_slab_volume(r, c, c - 0.001, c + 0.002),
              sphere_volume(r) - cap_volume(r, r - 0.001) - cap_volume(r, r - 0.002), 1e-18);
  // Outside (touching planes: zero up to the round-off of c + r - c, relative 1e-16 of the sphere),
  // and a thin slice at the equator: pi r^2 dz.
  EXPECT_NEAR(sphere_slab_volume(r, c, c + r, c + 2.0 * r), 0.0, 1e-13 * sphere_volume(r));
  EXPECT_NEAR(sphere_slab_volume(r, c, c - 3.0 * r, c - r), 0.0, 1e-13 * sphere_volume(r));
  EXPECT_NEAR(sphere_slab_volume(r, c, c + 1.1 * r, c + 2.0 * r), 0.0, 1e-13 * sphere_volume(r));
  EXPECT_NEAR(sphere_slab_volume(r, c, c - 1e-7, c + 1e-7), M_PI * r * r * 2e-7, 1e-6 * M_PI * r * r * 2e-7);
}

// Simple cubic packing of spheres of diameter d at spacing s: solids fraction (pi/6) (d/s)^3 in
// every zone of thickness s, whether the zones are aligned with the layers (each zone holds one
// layer) or shifted by half a spacing (each zone holds halves of two layers), and exactly by the
// partial volumes when the zone is thinner than a layer.
TEST(ZoneProfile, SolidsFractionOfSimpleCubicLattice) {
  const double d = 0.003, s = 0.0033;
  const int n = 4, layers = 6;
  const double expected = M_PI / 6.0 * std::pow(d / s, 3);
  ParticleStore p;
  for (int ix = 0; ix < n; ++ix)
    for (int iz = 0; iz < n; ++iz)
      for (int iy = 0; iy < layers; ++iy) add(p, {(ix + 0.5) * s, (iy + 0.5) * s, (iz + 0.5) * s}, 0.5 * d, 2500.0, {});
  // A fixed particle (a bump) is no part of the bed.
  add(p, {0.5 * s, 2.5 * s, 0.5 * s}, 0.5 * d, 2500.0, {}, Motion::wall_bump);
  const double area = (n * s) * (n * s);

  ZoneProfile aligned(1, 0.0, layers * s, s, area);
  aligned.sample(p);
  aligned.sample(p);
  const auto zones = aligned.averages();
  ASSERT_EQ(zones.size(), static_cast<std::size_t>(layers));
  for (const auto& z : zones) EXPECT_NEAR(z.solids_fraction, expected, 1e-12) << "zone at " << z.lo;

  ZoneProfile shifted(1, 0.5 * s, (layers - 0.5) * s, s, area);
  shifted.sample(p);
  for (const auto& z : shifted.averages()) EXPECT_NEAR(z.solids_fraction, expected, 1e-12) << "zone at " << z.lo;

  // Zones of a third of a spacing centred on a layer: the middle one holds the equatorial slice
  // [-s/6, s/6] of every sphere, the outer ones [s/6, s/2] (the caps beyond d/2 = 0.4545 s are cut).
  ZoneProfile thin(1, 2.0 * s, 3.0 * s, s / 3.0, area);
  thin.sample(p);
  const auto t = thin.averages();
  ASSERT_EQ(t.size(), 3u);
  const double r = 0.5 * d, zone_volume = area * s / 3.0;
  const double middle = n * n * sphere_slab_volume(r, 0.0, -s / 6.0, s / 6.0) / zone_volume;
  const double outer = n * n * sphere_slab_volume(r, 0.0, s / 6.0, s / 2.0) / zone_volume;
  EXPECT_NEAR(t[1].solids_fraction, middle, 1e-12);
  EXPECT_NEAR(t[0].solids_fraction, outer, 1e-12);
  EXPECT_NEAR(t[2].solids_fraction, outer, 1e-12);
  // Mass in a zone: the moving spheres' share.
  EXPECT_NEAR(zones[0].mass, n * n * 2500.0 * sphere_volume(r), 1e-12);
}

// Two samples of two spheres in one zone, masses m and 3m (radii in ratio 3^(1/3)), velocities
// chosen so that the instantaneous zone means (+2 and -2 on x) cancel in the long run:
//   sample 1: v_a = (1, 1, 0), v_b = (3, 1, 0);  sample 2: v_a = (-1, 1, 0), v_b = (-3, 1, 0)
// (the y velocities are a steady drift, the z ones zero). Per sample the mass-weighted mean on x is
// (m + 9m) / 4m = 2.5 and -2.5; long-term mean 0, y mean 1.
//   temperature_lan (about the instantaneous mean): x: [m (1.5)^2 + 3m (0.5)^2] / 4m = 0.75 per
//   sample, so 0.75; y, z: 0.
//   temperature_time_mean (about the long-term mean): x: [m 1 + 3m 9] 2 / 8m = 7; y, z: 0.
// They differ by the variance of the instantaneous mean, 2.5^2 = 6.25, as they must.
TEST(ZoneProfile, MeanVelocityAndBothTemperatures) {
  const double r_a = 0.001, r_b = 0.001 * std::cbrt(3.0), rho = 1000.0;
  const double m = rho * sphere_volume(r_a);
  ParticleStore p;
  add(p, {0.005, 0.005, 0.005}, r_a, rho, {1.0, 1.0, 0.0});
  add(p, {0.012, 0.005, 0.011}, r_b, rho, {3.0, 1.0, 0.0});
  const double area = 0.02 * 0.02, thickness = 0.01;
  ZoneProfile profile(1, 0.0, 0.01, thickness, area);
  profile.sample(p);
  p.velocity[0] = {-1.0, 1.0, 0.0};
  p.velocity[1] = {-3.0, 1.0, 0.0};
  profile.sample(p);
  EXPECT_EQ(profile.samples(), 2);
  const auto zones = profile.averages();
  ASSERT_EQ(zones.size(), 1u);
  const ZoneAverages& z = zones[0];
  EXPECT_NEAR(z.mass, 4.0 * m, 1e-15);
  EXPECT_NEAR(z.mean_velocity.x, 0.0, 1e-12);
  EXPECT_NEAR(z.mean_velocity.y, 1.0, 1e-12);
  EXPECT_NEAR(z.mean_velocity.z, 0.0, 1e-12);
  EXPECT_NEAR(z.temperature_lan.x, 0.75, 1e-12);
  EXPECT_NEAR(z.temperature_lan.y, 0.0, 1e-12);
  EXPECT_NEAR(z.temperature_lan.z, 0.0, 1e-12);
  EXPECT_NEAR(z.temperature_time_mean.x, 7.0, 1e-12);
  EXPECT_NEAR(z.temperature_time_mean.y, 0.0, 1e-12);
  EXPECT_NEAR(z.temperature_time_mean.x - z.temperature_lan.x, 2.5 * 2.5, 1e-12);
  // Kinetic energy density of the fluctuations about the instantaneous zone mean (Lan eq. 3-1-10):
  // (1/2) sum m |v - u|^2 / V, the same in both samples: (1/2) (m 1.5^2 + 3m 0.5^2) / V = 1.5 m / V.
  EXPECT_NEAR(z.kinetic_energy_density, 1.5 * m / (area * thickness), 1e-12 * m / (area * thickness));
  EXPECT_NEAR(z.solids_fraction, 4.0 * sphere_volume(r_a) / (area * thickness), 1e-12);
}

// A sphere cut by a zone boundary counts in both zones with its volume shares: centred on the
// boundary, half its mass and momentum in each. Zone 0 also holds a resting sphere, so its mean
// velocity is the mass-weighted (m v / 2 + m 0) / (3m / 2) = v / 3, and the moving sphere's
// fluctuation about that mean gives Lan's zone temperature (eq. 3-1-9, `temperature_lan`)
// [m/2 (2v/3)^2 + m (v/3)^2] / (3m/2) = 2 v^2 / 9.
TEST(ZoneProfile, SphereOnAZoneBoundaryIsSharedByVolume) {
  const double r = 0.001, rho = 1000.0, v = 0.6;
  ParticleStore p;
  add(p, {0.005, 0.004, 0.005}, r, rho, {v, 0.0, 0.0});     // on the boundary y = 0.004
  add(p, {0.005, 0.0015, 0.005}, r, rho, {0.0, 0.0, 0.0});  // inside zone 0 [0, 0.004)
  ZoneProfile profile(1, 0.0, 0.008, 0.004, 0.01 * 0.01);
  profile.sample(p);
  const auto zones = profile.averages();
  ASSERT_EQ(zones.size(), 2u);
  const double m = rho * sphere_volume(r);
  EXPECT_NEAR(zones[0].mass, 1.5 * m, 1e-15);
  EXPECT_NEAR(zones[1].mass, 0.5 * m, 1e-15);
  EXPECT_NEAR(zones[0].mean_velocity.x, v / 3.0, 1e-12);
  EXPECT_NEAR(zones[1].mean_velocity.x, v, 1e-12);
  EXPECT_NEAR(zones[0].temperature_lan.x, 2.0 * v * v / 9.0, 1e-12);
  EXPECT_NEAR(zones[1].temperature_lan.x, 0.0, 1e-12);
  // With one sample both temperatures coincide.
  EXPECT_NEAR(zones[0].temperature_time_mean.x, zones[0].temperature_lan.x, 1e-12);
}

// The last zone is cut by `hi` when the span is not a whole number of zones: its bounds, volume and
// partial volumes are those of the cut slab. A simple cubic lattice (spacing s, layers centred at
// (k + 1/2) s) in zones of thickness s from 0 to 2.4 s: the third zone [2 s, 2.4 s] holds the slice
// [-s/2, -0.1 s] of the third layer's spheres. Also with a single zone thinner than its thickness.
TEST(ZoneProfile, TopZoneCutByTheUpperBound) {
  const double d = 0.003, s = 0.0033, r = 0.5 * d, rho = 2500.0;
  const int n = 3;
  ParticleStore p;
  for (int ix = 0; ix < n; ++ix)
    for (int iz = 0; iz < n; ++iz)
      for (int iy = 0; iy < 3; ++iy) add(p, {(ix + 0.5) * s, (iy + 0.5) * s, (iz + 0.5) * s}, r, rho, {});
  const double area = (n * s) * (n * s);
  ZoneProfile profile(1, 0.0, 2.4 * s, s, area);
  profile.sample(p);
  const auto zones = profile.averages();
  ASSERT_EQ(zones.size(), 3u);
  EXPECT_NEAR(zones[2].lo, 2.0 * s, 1e-15);
  EXPECT_NEAR(zones[2].hi, 2.4 * s, 1e-15);
  const double slice = n * n * sphere_slab_volume(r, 0.0, -0.5 * s, -0.1 * s);
  EXPECT_NEAR(zones[2].solids_fraction, slice / (area * 0.4 * s), 1e-12);
  EXPECT_NEAR(zones[0].solids_fraction, M_PI / 6.0 * std::pow(d / s, 3), 1e-12);
  EXPECT_NEAR(zones[2].mass, rho * slice, 1e-12 * rho * slice);

  ZoneProfile single(1, 0.0, 0.4 * s, s, area);  // [0, 0.4 s]: the slice [-s/2, -0.1 s] of layer 0
  single.sample(p);
  const auto one = single.averages();
  ASSERT_EQ(one.size(), 1u);
  EXPECT_NEAR(one[0].hi, 0.4 * s, 1e-15);
  EXPECT_NEAR(one[0].solids_fraction, slice / (area * 0.4 * s), 1e-12);
}

// Along another axis (a chute with gravity along x, say): the profile uses that axis.
TEST(ZoneProfile, WorksAlongAnyAxis) {
  ParticleStore p;
  add(p, {0.0025, 0.3, -0.7}, 0.001, 1000.0, {0.0, 0.0, 2.0});
  ZoneProfile profile(0, 0.0, 0.005, 0.005, 1.0);
  profile.sample(p);
  const auto zones = profile.averages();
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_NEAR(zones[0].solids_fraction, sphere_volume(0.001) / 0.005, 1e-15);
  EXPECT_NEAR(zones[0].mean_velocity.z, 2.0, 1e-12);
}

// The instantaneous zone mean velocity (the histories behind Lan's spectra, section 4.3): mass
// weighted with partial volumes, not accumulated. A sphere centred on the boundary between zones 0
// and 1 gives half its mass to each; with a second, heavier sphere wholly in zone 0 the zone-0 mean
// is (m1 v1 / 2 + m2 v2) / (m1 / 2 + m2) exactly, zone 1 has the first sphere's velocity alone,
// and an empty zone reads zero. Calling it does not add a sample to the long-term averages.
TEST(ZoneProfile, InstantaneousMeanVelocityIsPartialVolumeWeighted) {
  ParticleStore p;
  const double r = 0.001, density = 2500.0;
  add(p, {0.005, 0.004, 0.005}, r, density, {0.0, 1.0, 0.0});          // centred on y = 0.004
  add(p, {0.005, 0.0015, 0.005}, r, 3.0 * density, {0.0, -2.0, 0.5});  // wholly in zone 0
  ZoneProfile profile(1, 0.0, 0.012, 0.004, 0.01 * 0.01);
  const auto u = profile.instantaneous_mean_velocity(p);
  ASSERT_EQ(u.size(), 3u);
  const double m1 = p.mass[0], m2 = p.mass[1];
  EXPECT_NEAR(u[0].y, (0.5 * m1 * 1.0 + m2 * -2.0) / (0.5 * m1 + m2), 1e-12);
  EXPECT_NEAR(u[0].z, m2 * 0.5 / (0.5 * m1 + m2), 1e-12);
  EXPECT_NEAR(u[1].y, 1.0, 1e-12);
  EXPECT_EQ(u[2].y, 0.0);
  EXPECT_EQ(profile.samples(), 0);
  const auto centre = profile.zone_centres();
  EXPECT_NEAR(centre[0], 0.002, 1e-15);
  EXPECT_NEAR(centre[2], 0.010, 1e-15);
}

// The bed's zone temperature at one instant (timeseries.csv's `zone_temperature`): the mass-weighted
// mean over zones of the zone temperatures, each about its zone's own instantaneous mean (eq. 3-1-9);
// not Lan's cell-average temperature, which is about the whole cell's mean velocity (eq. 3-1-2).
// Zone 0 holds two equal spheres moving at +-v along x about a common drift (its temperature is
// v^2 / 3 per degree of freedom), zone 1 a lone sphere (no fluctuation about its own mean), so the
// mass-weighted mean is (2m v^2 / 3) / (3m) = 2 v^2 / 9. A drift shared by the zone does not count,
// unlike in the cell-average temperature of GlobalSample, about the whole bed's mean velocity.
TEST(ZoneProfile, InstantaneousTemperatureIsAboutEachZonesMean) {
  ParticleStore p;
  const double r = 0.001, density = 2500.0, v = 0.3;
  add(p, {0.002, 0.0015, 0.005}, r, density, {v, 5.0, 0.0});
  add(p, {0.007, 0.0015, 0.005}, r, density, {-v, 5.0, 0.0});
  add(p, {0.005, 0.0055, 0.005}, r, density, {0.0, -7.0, 1.0});
  ZoneProfile profile(1, 0.0, 0.008, 0.004, 0.01 * 0.01);
  EXPECT_NEAR(profile.instantaneous_temperature(p), 2.0 * v * v / 9.0, 1e-12);
  EXPECT_EQ(profile.samples(), 0);
}

// Error bars of long-term averages by blocking: a sphere whose velocity is drawn afresh (iid) at
// every sample has a mean whose standard error is sigma / sqrt(n). With n = 4096 samples the blocks
// (merged in pairs whenever 512 are full) end as 256 of 16 samples; the blocking estimate then carries a relative
// uncertainty of about 1 / sqrt(2 (blocks - 1)) at its plateau level (>= 16 blocks: <= 18%), so 30% is a 1.7-sigma band
// on the worst level and a failing implementation (no sqrt(n), or per-block scatter unscaled, off by a factor >= 2.8)
// cannot pass. The solids fraction is constant: error zero.
TEST(ZoneProfile, BlockedErrorBarsMatchIidSamples) {
  ParticleStore p;
  add(p, {0.005, 0.002, 0.005}, 0.001, 2500.0, {});
  ZoneProfile profile(1, 0.0, 0.004, 0.004, 0.01 * 0.01);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> gauss(0.0, 1.0);
  const double sigma = 0.2;
  const int n = 4096;
  for (int s = 0; s < n; ++s) {
    p.velocity[0] = {sigma * gauss(rng), 0.0, 0.0};
    profile.sample(p);
  }
  EXPECT_EQ(profile.error_blocks(), 256);
  const auto zones = profile.averages();
  EXPECT_NEAR(zones[0].mean_velocity_error.x, sigma / std::sqrt(n), 0.3 * sigma / std::sqrt(n));
  EXPECT_NEAR(zones[0].solids_fraction_error, 0.0, 1e-15);
}

// Too few blocks for an error bar: NaN, not a misleading zero.
TEST(ZoneProfile, ErrorBarsAreNaNWithoutEnoughBlocks) {
  ParticleStore p;
  add(p, {0.005, 0.002, 0.005}, 0.001, 2500.0, {0.1, 0.0, 0.0});
  ZoneProfile profile(1, 0.0, 0.004, 0.004, 0.01 * 0.01);
  for (int s = 0; s < 10; ++s) profile.sample(p);
  EXPECT_TRUE(std::isnan(profile.averages()[0].solids_fraction_error));
}

// Along a periodic axis a sphere straddling the seam counts in the zones at both ends. Spheres on a
// lattice of spacing s along the axis, with s dividing both the zone thickness and the period, lay
// the same solid volume into every zone by translation symmetry, the last (half-thickness) zone
// included: nu is flat to round-off. Without the wrap the two seam zones read low by the caps that
// stick out of the box.
TEST(ZoneProfile, PeriodicAxisGivesFlatSolidsFractionInEveryZone) {
  const double r = 0.5, spacing = 0.5, lo = -1.0, period = 5.5, area = 3.0;  // 5 whole zones and a half
  const int spheres = static_cast<int>(std::lround(period / spacing));
  ParticleStore p;
  for (int k = 0; k < spheres; ++k) add(p, {0.0, lo + 0.13 + k * spacing, 0.0}, r, 1000.0, {});
  ZoneProfile profile(1, lo, lo + period, 1.0, area);
  profile.set_period();
  profile.sample(p);
  const auto zones = profile.averages();
  ASSERT_EQ(zones.size(), 6u);
  const double expected = spheres * sphere_volume(r) / (period * area);
  for (std::size_t z = 0; z < zones.size(); ++z) EXPECT_NEAR(zones[z].solids_fraction, expected, 1e-13) << "zone " << z;
}

// A sphere that crossed the seam but is not wrapped yet (positions are wrapped at rebuilds) counts
// where its wrapped self would: all of its volume lands in the box, in the same zones.
TEST(ZoneProfile, PeriodicAxisCountsAnUnwrappedSphereAsItsImage) {
  const double r = 0.4, lo = 0.0, period = 4.0;
  ParticleStore outside, inside;
  add(outside, {0.0, lo + period + 0.1, 0.0}, r, 1000.0, {});
  add(inside, {0.0, lo + 0.1, 0.0}, r, 1000.0, {});
  ZoneProfile a(1, lo, lo + period, 1.0, 1.0), b(1, lo, lo + period, 1.0, 1.0);
  a.set_period();
  b.set_period();
  a.sample(outside);
  b.sample(inside);
  double total = 0.0;
  for (std::size_t z = 0; z < a.averages().size(); ++z) {
    EXPECT_NEAR(a.averages()[z].solids_fraction, b.averages()[z].solids_fraction, 1e-15) << z;
    total += a.averages()[z].solids_fraction;
  }
  EXPECT_NEAR(total, sphere_volume(r), 1e-14);  // unit zone volumes: the fractions add to the volume
}

// Lees-Edwards: the image one period above moves faster by gamma_dot * L along x. A lattice of
// spheres moving exactly with the shear, v_x = gamma_dot y, gives every zone the same mass
// distribution, so u_x(zone) - gamma_dot * centre and Lan's temperature (from the spread of v_x over
// the zone) are the same in every zone, the seam zones included, to round-off. Counting the seam
// shares at the sphere's own velocity puts a velocity jump of gamma_dot L into the seam zones.
TEST(ZoneProfile, LeesEdwardsSeamZonesMatchTheInterior) {
  const double r = 0.5, spacing = 0.25, lo = 0.0, period = 5.5, rate = 2.0;
  ParticleStore p;
  for (int k = 0; k < static_cast<int>(std::lround(period / spacing)); ++k) {
    const double y = lo + 0.07 + k * spacing;
    add(p, {0.0, y, 0.0}, r, 1000.0, {rate * y, 0.0, 0.0});
  }
  ZoneProfile profile(1, lo, lo + period, 1.0, 1.0);
  profile.set_period({rate * period, 0.0, 0.0});
  profile.sample(p);
  const auto zones = profile.averages();
  const auto centres = profile.zone_centres();
  ASSERT_EQ(zones.size(), 6u);
  const double offset = zones[2].mean_velocity.x - rate * centres[2];
  for (std::size_t z = 0; z < zones.size(); ++z) {
    EXPECT_NEAR(zones[z].solids_fraction, zones[2].solids_fraction, 1e-13) << z;
    EXPECT_NEAR(zones[z].mean_velocity.x - rate * centres[z], offset, 1e-12) << z;
    // The half-thickness top zone holds half the spread of a whole zone: compare whole zones.
    if (z < 5) {
      EXPECT_NEAR(zones[z].temperature_lan.x, zones[2].temperature_lan.x, 1e-12) << z;
    }
  }
  EXPECT_GT(zones[2].temperature_lan.x, 0.01);  // the spread of v_x over a zone is not zero
}
