// Rolling on a wall (edmd/rolling.hpp) against the closed forms of a body rolling down an incline:
// without slip it accelerates at g sin(theta) / (1 + q), q = I / (m R^2) (2/5 for a solid sphere,
// 1/2 for a disc), and its spin is such that the contact point rests on the wall (omega R = v_t);
// on a smooth wall it slides at g sin(theta) and keeps its spin.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "grainflow/edmd/rolling.hpp"

using namespace grainflow;
using namespace grainflow::edmd;

namespace {

constexpr double kG = 9.81;
constexpr double kTheta = 25.0 * std::numbers::pi / 180.0;

// The chute's frame: flow along x, the bed (a ylo wall) normal along y.
EdmdWall bed(WallCondition condition) {
  EdmdWall w;
  w.face = 2;
  w.axis = 1;
  w.inward = 1.0;
  w.condition = condition;
  return w;
}

Vec3 gravity() { return {kG * std::sin(kTheta), -kG * std::cos(kTheta), 0.0}; }

// Velocity of the contact point (the point of the body touching the wall) relative to the wall.
Vec3 contact_slip(const EdmdWall& wall, const Vec3& v, const Vec3& spin, double radius) {
  Vec3 n;
  n[wall.axis] = wall.inward;
  return v - wall.velocity + cross(spin, -radius * n);
}

}  // namespace

TEST(Rolling, ASolidSphereRollsDownAnInclineAtFiveSeventhsOfGSinTheta) {
  const double mass = 2.0, radius = 0.5;
  const double inv_inertia = 1.0 / (0.4 * mass * radius * radius);
  for (WallCondition condition : {WallCondition::rough, WallCondition::no_slip}) {
    const Vec3 a = rolling_acceleration(gravity(), bed(condition), mass, inv_inertia, radius);
    EXPECT_NEAR(a.x, kG * std::sin(kTheta) / (1.0 + 2.0 / 5.0), 1e-12);
    EXPECT_EQ(a.y, 0.0);  // no acceleration into or off the wall
    EXPECT_EQ(a.z, 0.0);
  }
}

TEST(Rolling, ADiscRollsAtTwoThirdsOfGSinTheta) {
  const double mass = 3.0, radius = 1.5;
  const double inv_inertia = 1.0 / (0.5 * mass * radius * radius);
  const Vec3 a = rolling_acceleration(gravity(), bed(WallCondition::rough), mass, inv_inertia, radius);
  EXPECT_NEAR(a.x, 2.0 / 3.0 * kG * std::sin(kTheta), 1e-12);
  EXPECT_EQ(a.y, 0.0);
}

TEST(Rolling, OnASmoothWallItSlidesAtGSinThetaAndKeepsItsSpin) {
  const Vec3 a = rolling_acceleration(gravity(), bed(WallCondition::smooth), 1.0, 2.5, 1.0);
  EXPECT_DOUBLE_EQ(a.x, kG * std::sin(kTheta));
  EXPECT_EQ(a.y, 0.0);
  const Vec3 spin{0.3, -0.2, 7.0};
  const Vec3 kept = rolling_spin(bed(WallCondition::smooth), {2.0, 0.0, 1.0}, spin, 0.5);
  EXPECT_EQ(kept.x, spin.x);
  EXPECT_EQ(kept.y, spin.y);
  EXPECT_EQ(kept.z, spin.z);
}

// omega R = v_t: a sphere rolling at 2 m/s along x on the bed spins at -v / R about z (clockwise
// seen from +z), and in 3D a sideways speed adds spin about x; the spin about the wall's normal is
// the particle's own. On a moving wall it is the speed relative to the wall that counts.
TEST(Rolling, WithoutSlipTheContactPointRestsOnTheWall) {
  const double radius = 0.5;
  EdmdWall wall = bed(WallCondition::rough);
  const Vec3 v{2.0, 0.0, -0.6};
  const Vec3 spin = rolling_spin(wall, v, {1.0, 4.0, -3.0}, radius);
  EXPECT_NEAR(spin.z, -v.x / radius, 1e-12);
  EXPECT_NEAR(spin.x, v.z / radius, 1e-12);
  EXPECT_EQ(spin.y, 4.0);
  const Vec3 slip = contact_slip(wall, v, spin, radius);
  EXPECT_NEAR(norm(slip), 0.0, 1e-12);

  wall.velocity = {0.5, 0.0, 0.0};  // a sliding Couette wall
  const Vec3 moving = rolling_spin(wall, v, {}, radius);
  EXPECT_NEAR(moving.z, -(v.x - 0.5) / radius, 1e-12);
  EXPECT_NEAR(norm(contact_slip(wall, v, moving, radius)), 0.0, 1e-12);

  // On a ceiling (a yhi wall, normal -y) the same speed turns the other way.
  EdmdWall ceiling = bed(WallCondition::no_slip);
  ceiling.inward = -1.0;
  const Vec3 up = rolling_spin(ceiling, {2.0, 0.0, 0.0}, {}, radius);
  EXPECT_NEAR(up.z, 2.0 / radius, 1e-12);
  EXPECT_NEAR(norm(contact_slip(ceiling, {2.0, 0.0, 0.0}, up, radius)), 0.0, 1e-12);
}

TEST(RollingWalls, CountsTheParticlesThatRoll) {
  RollingWalls r;
  r.reset(4);
  EXPECT_FALSE(r.any());
  EXPECT_FALSE(r.rolls(2));
  r.set(2, 1);
  r.set(3, 0);
  EXPECT_TRUE(r.any());
  EXPECT_TRUE(r.rolls(2));
  EXPECT_EQ(r.wall(2), 1);
  EXPECT_EQ(r.wall(0), -1);
  r.set(2, 0);  // onto another wall: still one particle more
  r.set(3, -1);
  EXPECT_TRUE(r.rolls(2));
  EXPECT_FALSE(r.rolls(3));
  r.set(3, -1);  // freeing a free particle changes nothing
  r.set(2, -1);
  EXPECT_FALSE(r.any());
}
