// What the event-driven engine reports to a collision observer (edmd/collision_reports.hpp): the
// state before a collision, recovered from the state after it and the impulse, must be the one fed
// into collide_pair / collide_wall (collision_rules.hpp), for every restitution and wall condition.
#include <gtest/gtest.h>

#include <cmath>

#include "grainflow/edmd/collision_reports.hpp"
#include "grainflow/edmd/collision_rules.hpp"

using namespace grainflow;
using namespace grainflow::edmd;

namespace {

void expect_near(const Vec3& a, const Vec3& b, double tolerance) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

struct Body {
  Vec3 x, v, spin;
  double radius, mass, inertia;
  PairBody rule() { return {v, spin, radius, 1.0 / mass, 1.0 / inertia}; }
  Collided after() const { return {x, v, spin, radius, 1.0 / mass, 1.0 / inertia}; }
};

// Velocity of a body's contact point at -R n from its centre.
Vec3 contact_velocity(const Body& b, const Vec3& n) { return b.v + cross(b.spin, -b.radius * n); }

}  // namespace

// Rough inelastic spheres of unequal sizes hitting off centre: the report's relative velocity
// before is v_i - v_j as they came in, its normal the unit separation, its contact point on i's
// surface towards j, its impulse and dissipation those given.
TEST(CollisionReports, APairsRelativeVelocityBeforeIsTheOneThatCameIn) {
  for (double tangential : {-1.0, 0.0, 0.6}) {
    for (double e : {1.0, 0.7, 0.2}) {
      Body i{{1.0, 2.0, 0.5}, {0.8, -0.3, 0.2}, {0.5, 1.0, -2.0}, 0.5, 1.3, 0.4 * 1.3 * 0.25};
      Body j{{1.0 + 0.6, 2.0 + 0.8, 0.5}, {-0.4, -1.1, 0.1}, {-1.0, 0.2, 3.0}, 0.5, 0.7, 0.4 * 0.7 * 0.25};
      const Vec3 dr = i.x - j.x;  // |dr| = 1 = r_i + r_j: touching
      const Vec3 before = i.v - j.v;
      RestitutionLaw law;
      law.value = e;
      const Vec3 impulse = collide_pair(i.rule(), j.rule(), dr * (1.0 / norm(dr)), law, tangential);
      const auto c = pair_collision_report(4.5, 3, 8, i.after(), j.after(), dr, impulse, 0.125);
      expect_near(c.relative_velocity_before, before, 1e-14);
      EXPECT_EQ(c.time, 4.5);
      EXPECT_EQ(c.i, 3u);
      EXPECT_EQ(c.j, 8u);
      expect_near(c.normal, Vec3{-0.6, -0.8, 0.0}, 1e-15);
      expect_near(c.contact, i.x - 0.5 * c.normal, 1e-15);
      expect_near(c.xj, j.x, 0.0);
      EXPECT_EQ(c.impulse.x, impulse.x);
      EXPECT_EQ(c.dissipated, 0.125);
      // The rules' own check: the normal relative speed after is -e times that before.
      EXPECT_NEAR(dot(i.v - j.v, c.normal), -e * dot(before, c.normal), 1e-14);
    }
  }
}

// Across a sliding boundary the engine hands in j's image: its position i - dr and its velocity
// in the image's frame. The relative velocity is then the one i met.
TEST(CollisionReports, APairAcrossASlidingBoundaryIsReportedInTheImagesFrame) {
  Body i{{0.2, 0.1, 0.0}, {0.3, 0.5, 0.0}, {0.0, 0.0, 1.0}, 0.5, 1.0, 0.5 * 0.25};
  Body image{{0.2, 0.1 + 1.0, 0.0}, {-0.2 + 1.5, 0.4, 0.0}, {0.0, 0.0, -1.0}, 0.5, 1.0, 0.5 * 0.25};
  const Vec3 dr = i.x - image.x;
  const Vec3 before = i.v - image.v;
  RestitutionLaw law;
  law.value = 0.8;
  const Vec3 impulse = collide_pair(i.rule(), image.rule(), dr * (1.0 / norm(dr)), law, 0.0);
  const auto c = pair_collision_report(0.0, 0, 1, i.after(), image.after(), dr, impulse, 0.0);
  expect_near(c.relative_velocity_before, before, 1e-14);
  expect_near(c.xj, image.x, 0.0);
}

// The slip velocity before, the contact point's velocity relative to the wall along the wall,
// for rough, no-slip and smooth walls (the last also what a TC collision uses), moving or not.
TEST(CollisionReports, AWallsSlipVelocityBeforeIsTheOneThatCameIn) {
  for (WallCondition condition : {WallCondition::rough, WallCondition::no_slip, WallCondition::smooth}) {
    for (double wall_speed : {0.0, 1.5}) {
      EdmdWall wall;
      wall.face = 3;  // yhi: the normal into the box is -y
      wall.axis = 1;
      wall.inward = -1.0;
      wall.position = 5.0;
      wall.since = 1.0;
      wall.velocity = {wall_speed, 0.1, 0.0};
      const Vec3 n{0.0, -1.0, 0.0};
      Body p{{2.0, 4.5, 1.0}, {0.7, 1.2, -0.4}, {0.3, -2.0, 1.1}, 0.5, 1.0, 0.4 * 0.25};
      const Vec3 came_in = contact_velocity(p, n) - wall.velocity;
      const Vec3 slip_before = came_in - dot(came_in, n) * n;
      RestitutionLaw law;
      law.value = 0.6;
      const Vec3 impulse = collide_wall(p.rule(), n, wall.velocity, law, condition);
      const auto c = wall_collision_report(3.0, 7, 1, wall, p.after(), n, impulse, condition, 0.5);
      expect_near(c.slip_velocity_before, slip_before, 1e-14);
      EXPECT_EQ(c.i, 7u);
      EXPECT_EQ(c.wall, 1);
      expect_near(c.x, p.x, 0.0);
      EXPECT_DOUBLE_EQ(c.contact.y, 5.0 + 0.1 * (3.0 - 1.0));  // on the wall's plane at the time
      EXPECT_EQ(c.contact.x, p.x.x);
      EXPECT_EQ(c.dissipated, 0.5);
      if (condition == WallCondition::rough) {  // the contact point leaves with the wall's velocity
        const Vec3 out = contact_velocity(p, n) - wall.velocity;
        EXPECT_NEAR(norm(out - dot(out, n) * n), 0.0, 1e-14);
      }
    }
  }
}
