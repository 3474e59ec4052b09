// Exact share of a particle inside a slab between two planes: the sphere–slab volume of Lan's zone
// profiles (Fig. 3.1) and the disc–strip area of Campbell's strips (Fig. 2.11).
#pragma once

namespace grainflow::observe {

// Volume of a sphere of radius r centred at c lying between planes a < b (along one axis).
double sphere_slab_volume(double r, double c, double a, double b);

// Area of a disc of radius r centred at c lying between lines a < b (along one axis).
double disc_strip_area(double r, double c, double a, double b);

// Either of the above: disc area in 2D, sphere volume in 3D.
inline double particle_slab_measure(int dimension, double r, double c, double a, double b) {
  return dimension == 2 ? disc_strip_area(r, c, a, b) : sphere_slab_volume(r, c, a, b);
}

}  // namespace grainflow::observe
