// The mean flow a case starts its particles with (both engines, not with init = "file"):
// particles.initial_velocity, then Lees-Edwards' homogeneous shear (zero at mid-height) and the
// "couette" profile, linear across y from the ylo wall's velocity at domain.lo to the yhi wall's at
// domain.hi (Campbell section 2.8); or, with "campbell_chute", listing COL007's fit
// F(y / H) x initial_velocity (F(0) = 0.20, the wall slip; F(1) = 1), H the highest particle's
// height above domain.lo.
#pragma once

#include <algorithm>

#include "grainflow/config/case_config.hpp"

namespace grainflow {

class InitialFlow {
 public:
  // `height`: the highest particle centre above domain.lo along y (read by "campbell_chute" only).
  InitialFlow(const CaseConfig& c, double height) : c_(c), height_(height) {}

  Vec3 at(const Vec3& x) const {
    const ParticlesConfig& p = c_.particles;
    if (p.initial_profile == "campbell_chute") {
      static constexpr double kChuteFit[8] = {0.2018029,   3.5299215,  -15.2262754, 47.4364204,
                                              -88.1786499, 93.5828476, -51.8336868, 11.4877520};
      const double z = height_ > 0.0 ? std::clamp((x.y - c_.domain.lo.y) / height_, 0.0, 1.0) : 0.0;
      double f = 0.0;
      for (int k = 7; k >= 0; --k) f = f * z + kChuteFit[k];
      return f * p.initial_velocity;
    }
    Vec3 u = p.initial_velocity;
    if (c_.lees_edwards_rate != 0.0) u.x += c_.lees_edwards_rate * (x.y - 0.5 * (c_.domain.lo.y + c_.domain.hi.y));
    if (p.initial_profile == "couette") {
      const double fraction = (x.y - c_.domain.lo.y) / c_.domain.length(1);
      u += fraction * c_.walls[3].velocity + (1.0 - fraction) * c_.walls[2].velocity;
    }
    return u;
  }

 private:
  const CaseConfig& c_;
  double height_;
};

}  // namespace grainflow
