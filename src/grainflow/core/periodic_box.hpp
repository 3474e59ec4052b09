// The simulation box: its extent, which axes are periodic, minimum-image displacements and the
// image shifts a neighbor list refers to by a one-byte code: up to kMaxImage box lengths along each
// axis, so that a periodic width down to half a contact cutoff finds every image within reach.
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

  // Shift code: (sx+2) + 5 (sy+2) + 25 (sz+2) with s in {-2, ..., 2} box lengths; 62 is no shift,
  // and a code above it is a shift whose last nonzero component (z, then y, then x) is positive.
  static constexpr int kMaxImage = 2;
  static constexpr int kShiftBase = 2 * kMaxImage + 1;
  static constexpr int kShiftCodes = kShiftBase * kShiftBase * kShiftBase;
  static constexpr std::uint8_t kNoShift = kMaxImage * (1 + kShiftBase + kShiftBase * kShiftBase);
  static std::uint8_t shift_code(int sx, int sy, int sz) {
    return static_cast<std::uint8_t>((sx + kMaxImage) + kShiftBase * ((sy + kMaxImage) + kShiftBase * (sz + kMaxImage)));
  }
  static std::array<int, 3> shift_of(std::uint8_t code) {
    return {code % kShiftBase - kMaxImage, (code / kShiftBase) % kShiftBase - kMaxImage,
            code / (kShiftBase * kShiftBase) - kMaxImage};
  }
  std::array<Vec3, kShiftCodes> shift_table() const {
    std::array<Vec3, kShiftCodes> table{};
    for (int code = 0; code < kShiftCodes; ++code) {
      const auto s = shift_of(static_cast<std::uint8_t>(code));
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
