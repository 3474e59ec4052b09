#include "grainflow/analysis/partial_volume.hpp"

#include <algorithm>
#include <cmath>

namespace grainflow::observe {

double sphere_slab_volume(double r, double c, double a, double b) {
  // Antiderivative of the disc area pi (r^2 - h^2) along the axis, h measured from the centre.
  auto F = [r](double h) {
    h = std::clamp(h, -r, r);
    return M_PI * (r * r * h - h * h * h / 3.0);
  };
  return F(b - c) - F(a - c);
}

double disc_strip_area(double r, double c, double a, double b) {
  // Antiderivative of the chord length: F(h) = sign(h) (pi r^2 / 2 - segment(r - |h|)), with the
  // circular segment of height s written as 2 r^2 asin(sqrt(s / 2r)) - (r - s) sqrt(s (2r - s)):
  // well conditioned near the disc's edge, where h sqrt(r^2 - h^2) + r^2 asin(h / r) loses half
  // its digits (sqrt and asin of a cancelled difference).
  auto F = [r](double h) {
    h = std::clamp(h, -r, r);
    const double s = r - std::fabs(h);
    const double segment = 2.0 * r * r * std::asin(std::sqrt(s / (2.0 * r))) - (r - s) * std::sqrt(s * (2.0 * r - s));
    return std::copysign(0.5 * M_PI * r * r - segment, h);
  };
  return F(b - c) - F(a - c);
}

}  // namespace grainflow::observe
