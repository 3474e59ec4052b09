// Where the periodic images of a particle lie and how fast they move, for the event-driven engine:
// with Lees–Edwards boundaries (unbounded simple shear, flow x, gradient y) the image row above
// slides at U = shear rate x height, so it stands offset by U t along x; in a Couette cell whose
// width follows its gap (couette_servo.hpp) the images across x move at the width rate.
// Prediction and resolution must agree on both, or a touching pair is scheduled and skipped for ever.
#pragma once

#include <cmath>

#include "grainflow/core/periodic_box.hpp"
#include "grainflow/core/vec3.hpp"

namespace grainflow::edmd {

struct LeesEdwardsImages {
  double shear_velocity = 0.0;  // m/s, velocity of the image row above (shear rate x height); 0: plain periodic

  bool sliding() const { return shear_velocity != 0.0; }

  // Lees–Edwards offset of the image row above: U t modulo the width (U = shear rate x height).
  double offset(double width, double t) const {
    const double offset = std::fmod(shear_velocity * t, width);
    return offset < 0.0 ? offset + width : offset;
  }

  // Nearest-image separation xi - xj at time t (Lees–Edwards rows shifted by the offset).
  template <int Dim>
  Vec3 separation(const PeriodicBox& box, const Vec3& xi, const Vec3& xj, double t) const {
    if (!sliding()) return box.minimum_image(xi, xj);
    Vec3 d = xi - xj;
    const double k = std::nearbyint(d.y / box.length(1));
    d.y -= k * box.length(1);
    d.x -= k * offset(box.length(0), t);
    d.x -= box.length(0) * std::nearbyint(d.x / box.length(0));
    if (Dim == 3 && box.periodic[2]) d.z -= box.length(2) * std::nearbyint(d.z / box.length(2));
    return d;
  }

  // Velocity of the image of j (at xj) that i (at xi) meets at time t: images across a Lees–Edwards
  // boundary slide at U, and images across x move at `width_rate` (0 but in a Couette cell whose
  // width follows its gap).
  Vec3 image_velocity(const PeriodicBox& box, double width_rate, const Vec3& xi, const Vec3& xj, double t) const {
    Vec3 v;
    const Vec3 d = xi - xj;
    double rows = 0.0;
    if (sliding()) {
      rows = std::nearbyint(d.y / box.length(1));
      v.x += rows * shear_velocity;
    }
    if (width_rate != 0.0) {
      const double dx = d.x - rows * offset(box.length(0), t);
      v.x += std::nearbyint(dx / box.length(0)) * width_rate;
    }
    return v;
  }

  // A particle that left through a y face (k = +1 up, -1 down; y already brought back by a height)
  // becomes its image in the sliding row: shifted by the offset, moving with the row, and brought
  // back into [lo, hi) along x only (y sits on its face). Returns the widths it was moved back by.
  double enter_row(const PeriodicBox& box, int k, double t, Vec3& x, Vec3& v) const {
    x.x -= k * offset(box.length(0), t);
    v.x -= k * shear_velocity;
    const double width = box.length(0);
    const double turns = std::floor((x.x - box.lo.x) / width);
    x.x -= turns * width;
    return turns;
  }
};

}  // namespace grainflow::edmd
