// Savage and Jeffrey's (1981) collision-angle distribution for a sheared gas of discs with a
// Maxwellian velocity distribution about the local mean, as Campbell (1982 section 3.4.2) converts
// it to two dimensions and renormalises:
//   P(theta) = (1/pi) erfc(2^(-1/2) S cos(theta) sin(theta)),   0 <= theta < pi,
//   S = 2R (du/dy) / sqrt(<v'^2>),
// theta measured from the flow direction towards the velocity gradient. erfc is the standard one
// (2/sqrt(pi) times Campbell's printed integral, which without it would not integrate to 1): erf
// is odd and cos(theta) sin(theta) changes sign about pi/2, so the erf part integrates to zero and
// P integrates to 1 for every S; at S = 0 it is the isotropic 1/pi. For S > 0 collisions prefer
// 90 < theta < 180 degrees, where the faster layer above catches up with the slower one below.
#pragma once

namespace grainflow::analysis {

// Probability density per radian of the collision angle theta (radians) at shear parameter S.
double savage_jeffrey_angle_density(double theta, double shear_parameter);

// S = 2R (du/dy) / sqrt(<v'^2>); 0 when the fluctuation vanishes.
double savage_jeffrey_shear_parameter(double radius, double shear_rate, double mean_square_normal_velocity);

}  // namespace grainflow::analysis
