// The simulation box: its extent, which axes are periodic, minimum-image displacements and the
// 27 image shifts a neighbor list refers to by a one-byte code.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "grainflow/core/vec3.hpp"

namespace grainflow {

struct PeriodicBox {
  Vec3 lo, hi;
  std::array<bool, 3> periodic{};

  double length(int axis) const { return hi[axis] - lo[axis]; }

  // Shift code: (sx+1) + 3 (sy+1) + 9 (sz+1) with s in {-1, 0, 1} box lengths; 13 is no shift.
  static constexpr std::uint8_t kNoShift = 13;
  static std::uint8_t shift_code(int sx, int sy, int sz) {
    return static_cast<std::uint8_t>((sx + 1) + 3 * (sy + 1) + 9 * (sz + 1));
  }
  std::array<Vec3, 27> shift_table() const {
    std::array<Vec3, 27> table{};
    for (int code = 0; code < 27; ++code) {
      const int s[3] = {code % 3 - 1, (code / 3) % 3 - 1, code / 9 - 1};
      for (int axis = 0; axis < 3; ++axis) table[code][axis] = s[axis] * length(axis);
    }
    return table;
  }

  // Minimum-image displacement a - b (eq. 2-6-2, with rounding to the nearest image).
  Vec3 minimum_image(const Vec3& a, const Vec3& b) const {
    Vec3 d = a - b;
    for (int axis = 0; axis < 3; ++axis)
      if (periodic[axis]) d[axis] -= length(axis) * std::nearbyint(d[axis] / length(axis));
    return d;
  }

  // Wraps a position into [lo, hi) on periodic axes, counting the crossings in `image`.
  void wrap(Vec3& position, std::array<std::int32_t, 3>& image) const {
    for (int axis = 0; axis < 3; ++axis) {
      if (!periodic[axis]) continue;
      const double L = length(axis);
      const double k = std::floor((position[axis] - lo[axis]) / L);
      if (k != 0.0) {
        position[axis] -= k * L;
        if (position[axis] >= hi[axis]) position[axis] = lo[axis];  // round-off at the upper face
        image[axis] += static_cast<std::int32_t>(k);
      }
    }
  }

  Vec3 unwrapped(const Vec3& position, const std::array<std::int32_t, 3>& image) const {
    Vec3 out = position;
    for (int axis = 0; axis < 3; ++axis) out[axis] += image[axis] * length(axis);
    return out;
  }
};

}  // namespace grainflow
