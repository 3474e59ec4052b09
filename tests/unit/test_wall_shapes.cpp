// The wall types' geometry against closed forms: a plane's signed distance, a cylinder's from inside
// and outside, a cone's along its slant, the rims of open ends, a bounded disc's edge, the rigid
// motion of a shape and the surface velocity of a turning wall (v + w x r, exactly).
#include <gtest/gtest.h>

#include <cmath>

#include "grainflow/dem/dem_state.hpp"
#include "grainflow/walls/wall_types.hpp"

using namespace grainflow;
using namespace grainflow::walls;

namespace {

// Geometry of a few operations on numbers of order 1: a few ulps.
constexpr double kTight = 1e-14;

TEST(WallShapes, PlaneDistanceIsSignedAlongItsNormal) {
  PlaneWall w;
  w.point = {1.0, 2.0, 3.0};
  w.normal = Vec3{1.0, 1.0, 0.0} * (1.0 / std::sqrt(2.0));
  const SurfaceContact front = w.contact(0, {2.0, 3.0, 7.0});
  EXPECT_NEAR(front.gap, std::sqrt(2.0), kTight);
  EXPECT_NEAR(norm(front.normal - w.normal), 0.0, kTight);
  EXPECT_NEAR(w.contact(0, {0.0, 1.0, 0.0}).gap, -std::sqrt(2.0), kTight);  // behind: negative
}

TEST(WallShapes, AFacePlaneGivesTheFaceDistanceExactly) {
  // The box faces are planes with a unit axis normal: x[axis] - position, to the last bit.
  PlaneWall w;
  w.point = {0.0, 0.123456789, 0.0};
  w.normal = {0.0, -1.0, 0.0};
  const Vec3 x{0.3, 0.1000000000000001, 0.7};
  EXPECT_EQ(w.contact(0, x).gap, -1.0 * (x.y - 0.123456789));
}

TEST(WallShapes, CylinderInsideAndOutside) {
  CylinderWall c;
  c.point = {0.0, 0.0, 0.0};
  c.axis = {0.0, 0.0, 1.0};
  c.radius = 2.0;
  const Vec3 x{1.2, 0.9, 5.0};  // 1.5 from the axis
  const SurfaceContact in = c.contact(0, x);
  EXPECT_NEAR(in.gap, 0.5, kTight);
  EXPECT_NEAR(norm(in.normal - Vec3{-0.8, -0.6, 0.0}), 0.0, kTight);  // towards the axis
  c.inside = false;
  const SurfaceContact out = c.contact(0, x);
  EXPECT_NEAR(out.gap, -0.5, kTight);
  EXPECT_NEAR(norm(out.normal - Vec3{0.8, 0.6, 0.0}), 0.0, kTight);
}

TEST(WallShapes, FiniteCylinderHasRimsAndCaps) {
  CylinderWall c;
  c.point = {0.0, 0.0, 0.0};
  c.axis = {0.0, 0.0, 1.0};
  c.radius = 1.0;
  c.length = 4.0;
  // Beyond the top end, level with the wall: the rim is the nearest point, 0.5 above it.
  const SurfaceContact rim = c.contact(0, {1.0, 0.0, 4.5});
  EXPECT_NEAR(rim.gap, 0.5, kTight);
  EXPECT_NEAR(norm(rim.normal - Vec3{0.0, 0.0, 1.0}), 0.0, kTight);
  c.caps = true;
  EXPECT_EQ(c.elements(), 3);
  EXPECT_NEAR(c.contact(1, {0.2, 0.1, 0.3}).gap, 0.3, kTight);  // the bottom cap, normal +axis inside
  EXPECT_NEAR(c.contact(2, {0.2, 0.1, 3.0}).gap, 1.0, kTight);  // the top cap, normal -axis inside
}

TEST(WallShapes, ConeDistanceAlongItsSlant) {
  // A funnel opening upwards: radius 1 at the bottom (z = 0), 3 at z = 2; the slant rises at 45 degrees.
  ConeWall c;
  c.point = {0.0, 0.0, 0.0};
  c.axis = {0.0, 0.0, 1.0};
  c.radius_start = 1.0;
  c.radius_end = 3.0;
  c.length = 2.0;
  // On the axis's side of the slant at height 1 (wall radius 2), 1.5 from the axis: the perpendicular
  // distance to the 45-degree line is 0.5 / sqrt(2).
  const SurfaceContact s = c.contact(0, {1.5, 0.0, 1.0});
  EXPECT_NEAR(s.gap, 0.5 / std::sqrt(2.0), kTight);
  EXPECT_NEAR(norm(s.normal - Vec3{-1.0, 0.0, 1.0} * (1.0 / std::sqrt(2.0))), 0.0, kTight);
  // Below the outlet: the lower rim is nearest.
  EXPECT_NEAR(c.contact(0, {1.0, 0.0, -0.25}).gap, 0.25, kTight);
  // A cylinder is a cone of equal radii.
  c.radius_end = 1.0;
  EXPECT_NEAR(c.contact(0, {0.0, 0.6, 1.0}).gap, 0.4, kTight);
}

TEST(WallShapes, DiscPlaneHasAnEdge) {
  PlaneWall w;
  w.point = {0.0, 0.0, 0.0};
  w.normal = {0.0, 1.0, 0.0};
  w.bound = PlaneWall::Bound::disc;
  w.radius = 1.0;
  EXPECT_NEAR(w.contact(0, {0.5, 0.2, 0.0}).gap, 0.2, kTight);
  const SurfaceContact edge = w.contact(0, {1.3, 0.4, 0.0});  // beyond the edge: 0.5 from it
  EXPECT_NEAR(edge.gap, 0.5, kTight);
  EXPECT_NEAR(norm(edge.normal - Vec3{0.6, 0.8, 0.0}), 0.0, kTight);
}

// A silo's floor with an orifice: outside the hole the plane (from either side: particles pass
// through it), inside the nearest point of the hole's rim; the two agree where the foot meets the rim.
TEST(WallShapes, HoledPlaneIsTwoSidedWithARim) {
  PlaneWall w;
  w.point = {0.0, 0.0, 0.0};
  w.normal = {0.0, 1.0, 0.0};
  w.hole = 1.0;
  EXPECT_NEAR(w.contact(0, {2.0, 0.3, 0.0}).gap, 0.3, kTight);
  const SurfaceContact below = w.contact(0, {0.0, -0.3, 2.0});
  EXPECT_NEAR(below.gap, 0.3, kTight);
  EXPECT_NEAR(norm(below.normal - Vec3{0.0, -1.0, 0.0}), 0.0, kTight);
  const SurfaceContact rim = w.contact(0, {0.0, 0.4, 0.7});  // 0.3 inside the rim, 0.4 above: 0.5 from it
  EXPECT_NEAR(rim.gap, 0.5, kTight);
  EXPECT_NEAR(norm(rim.normal - Vec3{0.0, 0.8, -0.6}), 0.0, kTight);
  const SurfaceContact under = w.contact(0, {0.0, -0.4, -0.7});  // and from below
  EXPECT_NEAR(under.gap, 0.5, kTight);
  EXPECT_NEAR(norm(under.normal - Vec3{0.0, -0.8, 0.6}), 0.0, kTight);
  EXPECT_NEAR(w.contact(0, {1.0, 0.25, 0.0}).gap, 0.25, kTight);  // on the rim's line: both give 0.25
  EXPECT_NEAR(w.contact(0, {1.0 - 1e-12, 0.25, 0.0}).gap, 0.25, 1e-12);
}

TEST(WallShapes, RigidMotionTurnsAndShiftsTheShape) {
  PlaneWall w;
  w.point = {1.0, 0.0, 0.0};
  w.normal = {1.0, 0.0, 0.0};
  // A quarter turn about z through the origin, then a shift by (0, 0, 2).
  const RigidMotion m{{0.0, 0.0, 0.0}, {0.0, 0.0, 2.0}, Rotation::about({0.0, 0.0, M_PI / 2.0}, 1.0)};
  const PlaneWall moved = w.moved(m);
  EXPECT_NEAR(norm(moved.point - Vec3{0.0, 1.0, 2.0}), 0.0, kTight);
  EXPECT_NEAR(norm(moved.normal - Vec3{0.0, 1.0, 0.0}), 0.0, kTight);
  EXPECT_FALSE(w.spins_in_place({0.0, 0.0, 1.0}, {0.0, 0.0, 0.0}));
  EXPECT_TRUE(w.spins_in_place({3.0, 0.0, 0.0}, {5.0, 4.0, 1.0}));  // about its normal: in place
}

TEST(WallShapes, TurningWallSurfaceVelocityIsOmegaCrossR) {
  dem::DemWall drum;
  CylinderWall c;
  c.point = {0.5, -0.25, 0.0};
  c.axis = {0.0, 0.0, 1.0};
  c.radius = 2.0;
  drum.face = -1;
  drum.initial_shape = c;
  drum.angular_velocity = {0.0, 0.0, 3.0};
  drum.initial_origin = c.point;
  drum.turns = !c.spins_in_place(drum.angular_velocity, drum.initial_origin);
  EXPECT_FALSE(drum.turns);  // a drum about its own axis keeps its surface: no rotation applied
  drum.move_to(1.7);
  // At the wall's rightmost point, w x r = 3 z x 2 x = 6 y, exactly (the products are exact).
  const Vec3 v = drum.surface_velocity(c.point + Vec3{2.0, 0.0, 0.0});
  EXPECT_EQ(v.x, 0.0);
  EXPECT_EQ(v.y, 6.0);
  EXPECT_EQ(v.z, 0.0);
  const CylinderWall& now = std::get<CylinderWall>(drum.shape);
  EXPECT_EQ(now.point.x, c.point.x);  // unmoved, to the bit
  EXPECT_EQ(now.point.y, c.point.y);
}

}  // namespace
