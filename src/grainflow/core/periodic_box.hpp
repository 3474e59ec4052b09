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
  // Lees–Edwards boundaries (flow x, gradient y; soft spheres): the image row one height above
  // stands `shear_offset` further along x and moves at `shear_velocity` (shear rate x height). The
  // offset is U t less `shear_turns` widths, the turns taken off at neighbour-list rebuilds (between
  // two it grows smoothly, so that the listed images move smoothly). All zero: plain periodic.
  double shear_offset = 0.0, shear_velocity = 0.0;
  std::int32_t shear_turns = 0;
  bool sheared() const { return shear_velocity != 0.0; }

  double length(int axis) const { return hi[axis] - lo[axis]; }

  // Shift code: (sx+2) + 5 (sy+2) + 25 (sz+2) with s in {-2, ..., 2} box lengths; 62 is no shift,
  // and a code above it is a shift whose last nonzero component (z, then y, then x) is positive.
  static constexpr int kMaxImage = 2;
  static constexpr int kShiftBase = 2 * kMaxImage + 1;
  static constexpr int kShiftCodes = kShiftBase * kShiftBase * kShiftBase;
  static constexpr std::uint8_t kNoShift = kMaxImage * (1 + kShiftBase + kShiftBase * kShiftBase);
  static std::uint8_t shift_code(int sx, int sy, int sz) {
    return static_cast<std::uint8_t>((sx + kMaxImage) +
                                     kShiftBase * ((sy + kMaxImage) + kShiftBase * (sz + kMaxImage)));
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
      table[code].x += s[1] * shear_offset;
    }
    return table;
  }
  // The velocity of the image a shift code names, relative to the particle's own.
  Vec3 image_velocity(std::uint8_t code) const { return {shift_of(code)[1] * shear_velocity, 0.0, 0.0}; }

  // Minimum-image displacement a - b (eq. 2-6-2, with rounding to the nearest image).
  Vec3 minimum_image(const Vec3& a, const Vec3& b) const {
    Vec3 d = a - b;
    if (sheared()) {  // the row of images above or below first, then along x within it
      const double rows = std::nearbyint(d.y / length(1));
      d.y -= rows * length(1);
      d.x -= rows * shear_offset;
    }
    for (int axis = 0; axis < 3; ++axis)
      if (periodic[axis]) d[axis] -= length(axis) * std::nearbyint(d[axis] / length(axis));
    return d;
  }

  // Wraps a position into [lo, hi) on periodic axes, counting the crossings in `image`.
  // Under Lees–Edwards shear a particle leaving through a y face becomes its image in the sliding
  // row: moved by the offset along x and, with `velocity`, given the row's velocity. Its x crossings
  // count the turns taken off the offset so far, so that a pair's image key (contact_store.hpp)
  // stays the same across the crossing.
  void wrap(Vec3& position, std::array<std::int32_t, 3>& image, Vec3* velocity = nullptr) const {
    if (sheared()) {
      const double rows = std::floor((position.y - lo.y) / length(1));
      if (rows != 0.0) {
        position.y -= rows * length(1);
        if (position.y >= hi.y) position.y = lo.y;
        position.x -= rows * shear_offset;
        if (velocity) velocity->x -= rows * shear_velocity;
        const auto k = static_cast<std::int32_t>(rows);
        image[1] += k;
        image[0] -= k * shear_turns;
      }
    }
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
