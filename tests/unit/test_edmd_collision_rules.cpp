// Collision rules of the event-driven engine (src/grainflow/edmd/collision_rules.hpp) against
// Campbell 1982 section 2.11 (closed forms for rough discs on walls and on each other) and against
// the conservation laws every binary impulsive collision must obey.
//
// Conventions (Campbell's, checked against his governing equations): x along the flow, y up, spin
// counterclockwise about +z; Campbell's "omega" is the surface speed R omega_z; beta = (k/R)^2, so
// I = beta m R^2 (0.5 for his discs, 0.4 for solid spheres).
//
// All rules are a handful of floating-point operations on numbers of order 1: results must agree
// with the closed forms to a few ulps. The tolerance used is 1e-14 (absolute, on velocities of
// order 1-10), i.e. ~50 eps: a wrong factor or sign is O(1e-1), round-off O(1e-16).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/edmd/collision_rules.hpp"
#include "grainflow/edmd/edmd_state.hpp"

using namespace grainflow;
using namespace grainflow::edmd;

namespace {

constexpr double kTol = 1e-14;

RestitutionLaw constant_law(double e) {
  RestitutionLaw law;
  law.value = e;
  return law;
}

struct Body {
  Vec3 v, w;  // velocity, angular velocity
  double radius = 1.0, mass = 1.0, beta = 0.5;
  double inertia() const { return beta * mass * radius * radius; }
  PairBody pair() { return {v, w, radius, 1.0 / mass, 1.0 / inertia()}; }
  double energy() const { return 0.5 * mass * norm2(v) + 0.5 * inertia() * norm2(w); }
};

void expect_vec_near(const Vec3& a, const Vec3& b, double tol, const char* what) {
  EXPECT_NEAR(a.x, b.x, tol) << what << ".x";
  EXPECT_NEAR(a.y, b.y, tol) << what << ".y";
  EXPECT_NEAR(a.z, b.z, tol) << what << ".z";
}

// ---------------------------------------------------------------------------------------------
// Section 2.11.1: a rough disc on a wall. With e_w the wall restitution and no relative tangential
// velocity of the contact point on departure:
//   lower, stationary wall:  U = U0/(1+beta) - w0/(1+1/beta),          V = -e V0,
//                            w = beta/(1+beta) w0 - U0/(1+beta)
//   upper wall moving at U_T: U = U0/(1+beta) + (U_T + w0)/(1+1/beta),  V = -e V0,
//                            w = beta/(1+beta) w0 + (U0 - U_T)/(1+beta)
// (w = R omega_z). The "rough" wall condition is this rule.

class Campbell1982 : public ::testing::TestWithParam<double> {};  // beta

TEST_P(Campbell1982, StationaryLowerWall) {
  const double beta = GetParam(), e = 0.8;
  for (double radius : {1.0, 0.37}) {
    for (const auto& [U0, V0, w0] :
         {std::tuple{1.0, -2.0, 0.0}, std::tuple{-0.7, -0.3, 2.5}, std::tuple{3.0, -1.0, -4.0}}) {
      Body p{{U0, V0, 0.0}, {0.0, 0.0, w0 / radius}, radius, 2.3, beta};
      collide_wall(p.pair(), {0, 1, 0}, {}, constant_law(e), WallCondition::rough);
      EXPECT_NEAR(p.v.x, U0 / (1 + beta) - w0 / (1 + 1 / beta), kTol);
      EXPECT_NEAR(p.v.y, -e * V0, kTol);
      EXPECT_NEAR(radius * p.w.z, beta / (1 + beta) * w0 - U0 / (1 + beta), kTol);
      EXPECT_NEAR(p.v.x + radius * p.w.z, 0.0, kTol);  // contact point at rest on departure
      EXPECT_EQ(p.v.z, 0.0);
      EXPECT_EQ(p.w.x, 0.0);
      EXPECT_EQ(p.w.y, 0.0);
    }
  }
}

TEST_P(Campbell1982, MovingUpperWall) {
  const double beta = GetParam(), e = 0.8, UT = 1.5;
  for (const auto& [U0, V0, w0] : {std::tuple{1.0, 2.0, 0.0}, std::tuple{-0.7, 0.3, 2.5}, std::tuple{3.0, 1.0, -4.0}}) {
    Body p{{U0, V0, 0.0}, {0.0, 0.0, w0}, 1.0, 1.0, beta};
    collide_wall(p.pair(), {0, -1, 0}, {UT, 0, 0}, constant_law(e), WallCondition::rough);
    EXPECT_NEAR(p.v.x, U0 / (1 + beta) + (UT + w0) / (1 + 1 / beta), kTol);
    EXPECT_NEAR(p.v.y, -e * V0, kTol);
    EXPECT_NEAR(p.w.z, beta / (1 + beta) * w0 + (U0 - UT) / (1 + beta), kTol);
    EXPECT_NEAR(p.v.x - p.w.z, UT, kTol);  // contact point moves with the wall on departure
  }
}

// ---------------------------------------------------------------------------------------------
// Section 2.11.2: two equal rough discs in the centre-of-mass frame. A moves at U0 along k (the
// unit vector from A to B) and V0 along t = k x z; B moves opposite. Campbell's governing
// equations (U = U0 - J cos psi, V = V0 - J sin psi, w_A,B = w_A0,B0 + J sin psi / beta,
// U = -e U0, w_A + w_B - 2 V = 0) solve to
//   U = -e U0,  V = V0 + S / (2 (1 + 1/beta)),  w_A = w_A0 - S / (2 (1 + beta)),  same for B,
// with S = w_A0 + w_B0 - 2 V0. (The thesis prints the last three with the opposite sign of the
// S terms, which violates its own no-slip equation - it would double the slip and gain energy -
// so the printed signs are a typographical error; the solution of the stated equations is used.)

TEST_P(Campbell1982, ParticlePairInCentreOfMassFrame) {
  const double beta = GetParam(), e = 0.6;
  for (double theta : {0.0, 0.3, 2.0, -2.7}) {  // orientation of the line of centres
    const Vec3 k{std::cos(theta), std::sin(theta), 0.0};
    const Vec3 t = cross(k, Vec3{0, 0, 1});
    for (const auto& [U0, V0, wA0, wB0] : {std::tuple{1.0, 0.0, 0.0, 0.0}, std::tuple{1.0, 1.0, 0.0, 0.0},
                                           std::tuple{0.4, -0.8, 1.3, -0.2}, std::tuple{2.0, 0.5, -3.0, 2.0}}) {
      const double R = 0.8;
      Body A{U0 * k + V0 * t, {0, 0, wA0 / R}, R, 1.7, beta};
      Body B{-(U0 * k + V0 * t), {0, 0, wB0 / R}, R, 1.7, beta};
      collide_pair(A.pair(), B.pair(), -k /* from B to A */, constant_law(e), 0.0);
      const double S = wA0 + wB0 - 2 * V0;
      EXPECT_NEAR(dot(A.v, k), -e * U0, kTol);
      EXPECT_NEAR(dot(A.v, t), V0 + S / (2 * (1 + 1 / beta)), kTol);
      EXPECT_NEAR(R * A.w.z, wA0 - S / (2 * (1 + beta)), kTol);
      EXPECT_NEAR(R * B.w.z, wB0 - S / (2 * (1 + beta)), kTol);
      expect_vec_near(B.v, -A.v, kTol, "B mirrors A in the centre-of-mass frame");
      EXPECT_NEAR(R * (A.w.z + B.w.z) - 2 * dot(A.v, t), 0.0, kTol);  // Campbell's no-slip condition
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Beta, Campbell1982, ::testing::Values(0.5, 0.4));

// ---------------------------------------------------------------------------------------------
// General properties of collide_pair in 3D with unequal masses, radii and inertia factors.

struct PairSetup {
  Body i, j;
  Vec3 normal;  // from j to i
  Vec3 xi, xj;  // centres, touching
};

PairSetup random_pair(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.2, 1.0);
  PairSetup s;
  s.normal = Vec3{u(rng), u(rng), u(rng)};
  s.normal = s.normal * (1.0 / norm(s.normal));
  s.i = Body{
      {u(rng), u(rng), u(rng)}, {3 * u(rng), 3 * u(rng), 3 * u(rng)}, pos(rng), 3 * pos(rng), 0.2 + 0.4 * pos(rng)};
  s.j = Body{
      {u(rng), u(rng), u(rng)}, {3 * u(rng), 3 * u(rng), 3 * u(rng)}, pos(rng), 3 * pos(rng), 0.2 + 0.4 * pos(rng)};
  // Make them approach along the normal.
  const double vn = dot(s.i.v - s.j.v, s.normal);
  if (vn > 0) s.i.v -= (2 * vn + 0.1) * s.normal;
  s.xj = {u(rng), u(rng), u(rng)};
  s.xi = s.xj + (s.i.radius + s.j.radius) * s.normal;
  return s;
}

// Velocity of i's contact point relative to j's.
Vec3 contact_velocity(const PairSetup& s) {
  return s.i.v + cross(s.i.w, -s.i.radius * s.normal) - s.j.v - cross(s.j.w, s.j.radius * s.normal);
}

TEST(CollidePair, ConservesMomentumAndAngularMomentumAboutTheContactPoint) {
  // The impulse acts at the contact point c: each particle's angular momentum about c,
  // I w + m (x - c) x v, is unchanged, and so is the total linear momentum. Quantities are O(10):
  // 1e-13 absolute is ~50 ulps.
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    PairSetup s = random_pair(rng);
    const double e = unit(rng), b = 2 * unit(rng) - 1;
    const Vec3 c = s.xi - s.i.radius * s.normal;
    auto L = [&](const Body& body, const Vec3& x) {
      return body.inertia() * body.w + body.mass * cross(x - c, body.v);
    };
    const Vec3 p0 = s.i.mass * s.i.v + s.j.mass * s.j.v;
    const Vec3 Li0 = L(s.i, s.xi), Lj0 = L(s.j, s.xj);
    const Vec3 vi0 = s.i.v;
    const Vec3 J = collide_pair(s.i.pair(), s.j.pair(), s.normal, constant_law(e), b);
    expect_vec_near(s.i.mass * s.i.v + s.j.mass * s.j.v, p0, 1e-13, "momentum");
    expect_vec_near(L(s.i, s.xi), Li0, 1e-13, "L_i about the contact point");
    expect_vec_near(L(s.j, s.xj), Lj0, 1e-13, "L_j about the contact point");
    expect_vec_near(J, s.i.mass * (s.i.v - vi0), 1e-13, "returned impulse on i");
    EXPECT_GT(dot(J, s.normal), 0.0);  // repulsive
  }
}

TEST(CollidePair, NormalAndTangentialRestitution) {
  // After the collision the normal relative velocity is -e times, and the tangential velocity of
  // the contact points -b times, what it was; the energy lost is exactly
  //   (1 - e^2)/2 mu_n vn^2 + (1 - b^2)/2 mu_t |slip|^2,
  // mu_n = 1/(1/m_i + 1/m_j), 1/mu_t = 1/m_i + 1/m_j + R_i^2/I_i + R_j^2/I_j (the normal impulse
  // passes through the centres; the tangential one does not change the normal velocity).
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 2000; ++k) {
    PairSetup s = random_pair(rng);
    const double e = k % 4 == 0 ? 1.0 : unit(rng);
    const double b = k % 3 == 0 ? 1.0 : (k % 3 == 1 ? 0.0 : 2 * unit(rng) - 1);
    const Vec3 g0 = contact_velocity(s);
    const double vn0 = dot(g0, s.normal);
    const Vec3 slip0 = g0 - vn0 * s.normal;
    const double E0 = s.i.energy() + s.j.energy();
    collide_pair(s.i.pair(), s.j.pair(), s.normal, constant_law(e), b);
    const Vec3 g1 = contact_velocity(s);
    const double vn1 = dot(g1, s.normal);
    EXPECT_NEAR(vn1, -e * vn0, 1e-14 * 10);
    expect_vec_near(g1 - vn1 * s.normal, -b * slip0, 1e-13, "slip");
    const double mu_n = 1 / (1 / s.i.mass + 1 / s.j.mass);
    const double mu_t = 1 / (1 / s.i.mass + 1 / s.j.mass + s.i.radius * s.i.radius / s.i.inertia() +
                             s.j.radius * s.j.radius / s.j.inertia());
    const double loss = 0.5 * (1 - e * e) * mu_n * vn0 * vn0 + 0.5 * (1 - b * b) * mu_t * norm2(slip0);
    // Energies O(10-100): 1e-12 absolute is ~50 ulps of the sum.
    EXPECT_NEAR(E0 - (s.i.energy() + s.j.energy()), loss, 1e-12);
  }
}

TEST(CollidePair, ElasticRoughConservesEnergy) {
  // e = 1, b = +1 (perfectly elastic rough): translational + rotational energy conserved.
  std::mt19937_64 rng(44);
  for (int k = 0; k < 1000; ++k) {
    PairSetup s = random_pair(rng);
    const double E0 = s.i.energy() + s.j.energy();
    collide_pair(s.i.pair(), s.j.pair(), s.normal, constant_law(1.0), 1.0);
    EXPECT_NEAR(s.i.energy() + s.j.energy(), E0, 1e-13 * E0);
  }
}

TEST(CollidePair, SmoothLeavesSpinsAndTangentialVelocitiesAlone) {
  // b = -1: a frictionless impulse along the normal; spins bit-for-bit unchanged, tangential
  // centre velocities unchanged to round-off, normal ones exchanged as for smooth spheres.
  std::mt19937_64 rng(45);
  for (int k = 0; k < 1000; ++k) {
    PairSetup s = random_pair(rng);
    const Vec3 wi = s.i.w, wj = s.j.w, vi = s.i.v, vj = s.j.v;
    const double E0 = s.i.energy() + s.j.energy();
    collide_pair(s.i.pair(), s.j.pair(), s.normal, constant_law(1.0), -1.0);
    EXPECT_EQ(s.i.w, wi);
    EXPECT_EQ(s.j.w, wj);
    auto tangential = [&](const Vec3& v) { return v - dot(v, s.normal) * s.normal; };
    expect_vec_near(tangential(s.i.v), tangential(vi), 1e-14, "i tangential");
    expect_vec_near(tangential(s.j.v), tangential(vj), 1e-14, "j tangential");
    EXPECT_NEAR(s.i.energy() + s.j.energy(), E0, 1e-13 * E0);  // elastic smooth
  }
}

TEST(CollidePair, HeadOnEqualMassesExchangeVelocities) {
  // The textbook case: equal smooth spheres, e = 1, head on: velocities exchanged exactly.
  Body a{{1, 0, 0}, {}, 0.5, 1.0, 0.4}, b{{-0.25, 0, 0}, {}, 0.5, 1.0, 0.4};
  collide_pair(b.pair(), a.pair(), {1, 0, 0}, constant_law(1.0), -1.0);
  EXPECT_NEAR(a.v.x, -0.25, 1e-15);
  EXPECT_NEAR(b.v.x, 1.0, 1e-15);
  // e = 0.5, m_a = 3 m_b: v_a' = v_cm - e m_b/(m_a+m_b) dv, etc.
  Body c{{1, 0, 0}, {}, 0.5, 3.0, 0.4}, d{{-1, 0, 0}, {}, 0.5, 1.0, 0.4};
  collide_pair(d.pair(), c.pair(), {1, 0, 0}, constant_law(0.5), -1.0);
  const double vcm = (3.0 * 1 + 1.0 * -1) / 4.0;      // 0.5
  EXPECT_NEAR(c.v.x, vcm - 0.5 * 0.25 * 2.0, 1e-15);  // 0.25
  EXPECT_NEAR(d.v.x, vcm + 0.5 * 0.75 * 2.0, 1e-15);  // 1.25
}

// ---------------------------------------------------------------------------------------------
// Walls: the three conditions and a wall moving along its normal.

TEST(CollideWall, NoSlipSetsCentreTangentialVelocityToTheWalls) {
  // Campbell's "no-slip" condition: the centre leaves with the wall's tangential velocity, the spin
  // is untouched, the normal velocity relative to the wall is reversed times e.
  std::mt19937_64 rng(46);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 500; ++k) {
    const Vec3 wall{2 * u(rng), 0.0, 2 * u(rng)};  // sliding in the wall plane y = const
    Body p{{u(rng), -0.1 - std::fabs(u(rng)), u(rng)}, {u(rng), u(rng), u(rng)}, 0.5, 1.3, 0.4};
    const Vec3 w0 = p.w;
    const double vy0 = p.v.y;
    collide_wall(p.pair(), {0, 1, 0}, wall, constant_law(0.7), WallCondition::no_slip);
    EXPECT_NEAR(p.v.x, wall.x, kTol);
    EXPECT_NEAR(p.v.z, wall.z, kTol);
    EXPECT_NEAR(p.v.y, -0.7 * vy0, kTol);
    EXPECT_EQ(p.w, w0);
  }
}

TEST(CollideWall, SmoothKeepsTangentialVelocityAndSpin) {
  Body p{{0.3, -1.0, -0.2}, {1.0, 2.0, 3.0}, 0.5, 1.0, 0.4};
  collide_wall(p.pair(), {0, 1, 0}, {5.0, 0, 0}, constant_law(0.5), WallCondition::smooth);
  EXPECT_NEAR(p.v.x, 0.3, kTol);
  EXPECT_NEAR(p.v.z, -0.2, kTol);
  EXPECT_NEAR(p.v.y, 0.5, kTol);
  EXPECT_EQ(p.w, (Vec3{1.0, 2.0, 3.0}));
}

TEST(CollideWall, RoughIn3DStopsTheContactPointAndConservesAngularMomentumAboutIt) {
  // Random walls (any normal), 3D spins: after a rough-wall collision the contact point moves with
  // the wall tangentially; the particle's angular momentum about the contact point is conserved.
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 1000; ++k) {
    Vec3 n{u(rng), u(rng), u(rng)};
    n = n * (1.0 / norm(n));
    Vec3 wall{u(rng), u(rng), u(rng)};
    wall -= dot(wall, n) * n;  // tangential wall motion
    Body p{{u(rng), u(rng), u(rng)},
           {3 * u(rng), 3 * u(rng), 3 * u(rng)},
           0.2 + std::fabs(u(rng)),
           1.0 + u(rng) * 0.5,
           0.4};
    const double vn = dot(p.v - wall, n);
    if (vn > 0) p.v -= (2 * vn + 0.1) * n;
    const double vn0 = dot(p.v - wall, n);
    const Vec3 r = -p.radius * n;                                 // from the centre to the contact point
    const Vec3 L0 = p.inertia() * p.w + p.mass * cross(-r, p.v);  // about the contact point
    collide_wall(p.pair(), n, wall, constant_law(0.8), WallCondition::rough);
    const Vec3 contact = p.v + cross(p.w, r) - wall;
    EXPECT_NEAR(dot(contact, n), -0.8 * vn0, 1e-14 * 10);
    expect_vec_near(contact - dot(contact, n) * n, {}, 1e-13, "contact slip");
    expect_vec_near(p.inertia() * p.w + p.mass * cross(-r, p.v), L0, 1e-13, "L about the contact point");
  }
}

TEST(CollideWall, WallMovingAlongItsNormal) {
  // A wall at velocity w_n along its normal (the pressure servo): the velocity relative to the
  // wall is reversed times e: v' - w_n = -e (v - w_n). A wall receding at 1 hit by a particle at 3:
  // v' = 1 - 0.5 (3 - 1) = 0 ... along the inward normal -y of an upper wall.
  Body p{{0.0, 3.0, 0.0}, {}, 0.5, 1.0, 0.4};
  collide_wall(p.pair(), {0, -1, 0}, {0, 1.0, 0}, constant_law(0.5), WallCondition::smooth);
  EXPECT_NEAR(p.v.y, 0.0, kTol);
  Body q{{0.0, 2.0, 0.0}, {}, 0.5, 1.0, 0.4};
  collide_wall(q.pair(), {0, -1, 0}, {0, -1.0, 0}, constant_law(1.0), WallCondition::smooth);
  EXPECT_NEAR(q.v.y, -4.0, kTol);  // elastic reflection off an approaching wall: 2 w_n - v
}

// ---------------------------------------------------------------------------------------------
// Restitution laws.

TEST(RestitutionLaw, ConstantCampbellAndElasticBelow) {
  RestitutionLaw constant = constant_law(0.6);
  EXPECT_EQ(constant(0.0), 0.6);
  EXPECT_EQ(constant(100.0), 0.6);
  // Campbell's reconstructed law e = (1 + exp(-3 dv / scale)) / 2: 1 at rest, (1 + e^-3)/2 =
  // 0.52489 at dv = scale, 1/2 for violent impacts.
  RestitutionLaw campbell;
  campbell.kind = RestitutionLaw::Kind::campbell;
  campbell.velocity_scale = 2.0;
  EXPECT_DOUBLE_EQ(campbell(0.0), 1.0);
  EXPECT_DOUBLE_EQ(campbell(2.0), 0.5 * (1.0 + std::exp(-3.0)));
  EXPECT_DOUBLE_EQ(campbell(0.2), 0.5 * (1.0 + std::exp(-0.3)));
  EXPECT_NEAR(campbell(1e3), 0.5, 1e-15);
  // Elastic below a small impact speed, for either kind.
  RestitutionLaw below = constant_law(0.5);
  below.elastic_speed = 0.1;
  EXPECT_EQ(below(0.05), 1.0);
  EXPECT_EQ(below(0.1), 0.5);
  EXPECT_EQ(below(0.2), 0.5);
  campbell.elastic_speed = 0.1;
  EXPECT_EQ(campbell(0.099), 1.0);
  EXPECT_DOUBLE_EQ(campbell(0.2), 0.5 * (1.0 + std::exp(-0.3)));
}

TEST(RestitutionLaw, CollisionsUseTheNormalImpactSpeed) {
  // A head-on collision at normal speed dv (plus a tangential component, which must not enter the
  // impact speed): the normal relative velocity after is -e(dv) dv.
  RestitutionLaw campbell;
  campbell.kind = RestitutionLaw::Kind::campbell;
  campbell.velocity_scale = 1.5;
  campbell.elastic_speed = 0.05;
  for (double dv : {0.01, 0.3, 1.5, 6.0}) {
    Body a{{dv, 0.7, 0.0}, {}, 0.5, 1.0, 0.4}, b{{0, 0, 0}, {}, 0.5, 1.0, 0.4};
    collide_pair(b.pair(), a.pair(), {1, 0, 0}, campbell, -1.0);
    EXPECT_NEAR(a.v.x - b.v.x, -campbell(dv) * dv, kTol) << dv;  // before: +dv (closing)
    Body w{{0.3, -dv, 0}, {}, 0.5, 1.0, 0.4};
    collide_wall(w.pair(), {0, 1, 0}, {}, campbell, WallCondition::rough);
    EXPECT_NEAR(w.v.y, campbell(dv) * dv, kTol) << dv;
  }
  EXPECT_EQ(campbell(0.01), 1.0);  // the first speed is in the elastic range
}

TEST(RestitutionLaw, FromTheCaseFile) {
  // [collision] keys reach the state's laws: campbell with a velocity scale, elastic_speed, a wall
  // restitution; without velocity_scale the scale is sqrt(g R) (Campbell's unit), and without
  // rolling_speed the threshold is his listing's 1e-4 sqrt(g R).
  const std::string base = R"([engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [10.0, 10.0, 1.0]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[gravity]
vector = [0.0, -4.0, 0.0]
[[species]]
name = "disc"
diameter = 0.5
density = 1.0
count = 4
[particles]
init = "lattice"
[run]
duration = 1.0
)";
  {
    const CaseConfig c = load_case_from_string(base + R"([collision]
restitution = 0.6
restitution_law = "campbell"
velocity_scale = 2.5
elastic_speed = 0.01
wall_restitution = 0.8
roughness = "rough"
)",
                                               "campbell.toml");
    const EdmdState s = build_edmd_state(c);
    EXPECT_EQ(s.restitution.kind, RestitutionLaw::Kind::campbell);
    EXPECT_EQ(s.restitution.velocity_scale, 2.5);
    EXPECT_EQ(s.restitution.elastic_speed, 0.01);
    EXPECT_EQ(s.tangential_restitution, 0.0);
    ASSERT_EQ(s.walls.size(), 1u);
    EXPECT_EQ(s.walls[0].restitution.value, 0.8);
  }
  {
    const CaseConfig c = load_case_from_string(base + R"([collision]
restitution_law = "campbell"
tangential_restitution = 0.5
)",
                                               "default_scale.toml");
    const EdmdState s = build_edmd_state(c);
    EXPECT_DOUBLE_EQ(s.restitution.velocity_scale, std::sqrt(4.0 * 0.25));  // sqrt(g R), R = 0.25
    EXPECT_EQ(s.tangential_restitution, 0.5);
    // Under gravity rolling starts below Campbell's 1e-4 sqrt(g R) unless the case says otherwise.
    EXPECT_DOUBLE_EQ(s.rolling_speed, 1e-4 * std::sqrt(4.0 * 0.25));
  }
}

}  // namespace
