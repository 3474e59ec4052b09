// A plane wall on a face of the box, the part of a wall both engines and every observer share:
// which face it closes, the axis normal to it, the side the particles lie on and where it is.
// The soft-sphere engine's walls (dem/dem_state.hpp) add their motion and contact keys, the
// event-driven engine's (edmd/edmd_state.hpp) their collision rule; an observer reads any of them
// through FaceWalls without knowing which engine moves them.
#pragma once

#include <cstddef>
#include <vector>

#include "grainflow/core/vec3.hpp"

namespace grainflow {

// What a wall does beyond where it is: the servo, the strip layouts and the observers ask for the
// walls of a shear cell by role, not by face. The box's walls across the shear gradient (y) play
// them (face_roles); the servo moves both.
enum class WallRole : unsigned {
  shear_bottom = 1,  // the low wall across the shear gradient: a Couette cell's bottom, a chute's floor
  shear_top = 2,     // the high one: a Couette cell's moving top
};
// The roles a box face plays.
constexpr unsigned face_roles(int face) {
  return face == 2 ? static_cast<unsigned>(WallRole::shear_bottom)
                   : face == 3 ? static_cast<unsigned>(WallRole::shear_top) : 0u;
}

struct FaceWall {
  int face = 0;  // axis * 2 + (0 low, 1 high)
  unsigned roles = 0;  // WallRole bits
  bool plays(WallRole role) const { return (roles & static_cast<unsigned>(role)) != 0; }
  int axis = 0;
  double inward = 1.0;    // +1 on a low face (normal +e_axis), -1 on a high face
  double position = 0.0;  // m, plane coordinate at time `since`
  double since = 0.0;     // s
  Vec3 velocity;          // m/s; the normal component moves the plane

  // The plane's coordinate at time t, moving at its present velocity.
  double at(double t) const { return position + velocity[axis] * (t - since); }
  // The unit normal pointing into the box.
  Vec3 normal() const {
    Vec3 n;
    n[axis] = inward;
    return n;
  }
  // Distance from the plane (at time t) to a point on the particles' side; negative behind it.
  double distance(const Vec3& x, double t) const { return inward * (x[axis] - at(t)); }
};

// The index of the wall in `walls` (any engine's walls, or a FaceWalls view) playing `role`, or -1.
template <class Walls>
int wall_with_role(const Walls& walls, WallRole role) {
  for (std::size_t w = 0; w < walls.size(); ++w)
    if (walls[w].plays(role)) return static_cast<int>(w);
  return -1;
}

// A read-only view of an engine's box-face walls as FaceWalls (each engine's wall type derives from
// it): indices are the engine's, and the view follows the walls as they move.
class FaceWalls {
 public:
  FaceWalls() = default;
  // The box faces lead an engine's walls (face >= 0); walls of other shapes after them are not faces.
  template <class Wall>
  explicit FaceWalls(const std::vector<Wall>& walls)
      : first_(walls.empty() ? nullptr
                             : reinterpret_cast<const unsigned char*>(static_cast<const FaceWall*>(walls.data()))),
        stride_(sizeof(Wall)) {
    while (count_ < walls.size() && walls[count_].face >= 0) ++count_;
  }

  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const FaceWall& operator[](std::size_t w) const { return *reinterpret_cast<const FaceWall*>(first_ + w * stride_); }
  struct Iterator {
    const FaceWalls* walls;
    std::size_t w;
    const FaceWall& operator*() const { return (*walls)[w]; }
    Iterator& operator++() {
      ++w;
      return *this;
    }
    bool operator!=(const Iterator& o) const { return w != o.w; }
  };
  Iterator begin() const { return {this, 0}; }
  Iterator end() const { return {this, count_}; }
  // The index of the wall playing `role`, or -1.
  int with_role(WallRole role) const { return wall_with_role(*this, role); }
  // The index of the wall on `face`, or -1.
  int on_face(int face) const {
    for (std::size_t w = 0; w < count_; ++w)
      if ((*this)[w].face == face) return static_cast<int>(w);
    return -1;
  }

 private:
  const unsigned char* first_ = nullptr;
  std::size_t stride_ = 0, count_ = 0;
};

}  // namespace grainflow
