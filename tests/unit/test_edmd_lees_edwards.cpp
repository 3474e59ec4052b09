// Lees–Edwards boundaries (unbounded simple shear) in the event-driven engine: the image rows slide
// at U = shear_rate x height, particles crossing the y faces become their sliding images, and
// collisions across the boundary are resolved in the image's frame. Then the images on their own
// (edmd/lees_edwards.hpp) against closed forms.
#include <gtest/gtest.h>

#include <cmath>

#include "grainflow/run/case_loader.hpp"
#include "grainflow/edmd/edmd_engine.hpp"
#include "grainflow/edmd/lees_edwards.hpp"
#include "grainflow/observe/strip_profile.hpp"

using namespace grainflow;

namespace {

constexpr double kRate = 0.1;   // 1/s
constexpr double kSide = 30.0;  // box side, diameters (d = 1)
constexpr int kDiscs = 400;     // area fraction 400 pi / 4 / 900 = 0.35

std::string sheared_gas(double restitution) {
  return "[engine]\nkind = \"edmd\"\ndimension = 2\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [30.0, 30.0, 1.0]\n"
         "boundary = { x = \"periodic\", y = \"periodic\", z = \"periodic\" }\n[gravity]\nvector = [0.0, 0.0, 0.0]\n"
         "[[species]]\nname = \"disc\"\ndiameter = 1.0\ndensity = 1.2732395447351628\ncount = 400\n"
         "[particles]\ninit = \"random\"\ninitial_temperature = 0.01\nseed = 3\n[collision]\nrestitution = " +
         std::to_string(restitution) + "\n[lees_edwards]\nshear_rate = 0.1\n[run]\nduration = 300.0\n";
}

// Smallest centre distance over all pairs, with the Lees–Edwards image convention at time t.
double closest_pair(const ParticleStore& p, double t) {
  const double offset = std::fmod(kRate * kSide * t, kSide);
  double closest = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + 1; j < p.size(); ++j) {
      double dx = p.position[i].x - p.position[j].x, dy = p.position[i].y - p.position[j].y;
      const double k = std::nearbyint(dy / kSide);
      dy -= k * kSide;
      dx -= k * offset;
      dx -= kSide * std::nearbyint(dx / kSide);
      closest = std::min(closest, std::hypot(dx, dy));
    }
  return closest;
}

// Least-squares slope of v_x against y, and the temperature of the fluctuations about that profile.
std::pair<double, double> shear_profile(const ParticleStore& p) {
  double my = 0, mv = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    my += p.position[i].y;
    mv += p.velocity[i].x;
  }
  my /= p.size();
  mv /= p.size();
  double sxy = 0, syy = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    sxy += (p.position[i].y - my) * (p.velocity[i].x - mv);
    syy += (p.position[i].y - my) * (p.position[i].y - my);
  }
  const double slope = sxy / syy;
  double t = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double u = p.velocity[i].x - mv - slope * (p.position[i].y - my);
    t += 0.5 * (u * u + p.velocity[i].y * p.velocity[i].y);
  }
  return {slope, t / p.size()};
}

}  // namespace

// Inelastic discs under Lees–Edwards shear keep the imposed linear profile (its slope is the shear
// rate: the boundaries impose nothing else) and never overlap. The fitted slope of 400 discs with
// T ~ 0.04 scatters by about sqrt(T / N) / std(y) ~ 0.01 / 8.7 ~ 1e-3, 1% of the rate: 5% is ample
// yet fails for a sign error or a missing image velocity (slope drifting to 0 or doubling).
TEST(EdmdLeesEdwards, InelasticDiscsKeepTheImposedShearAndNeverOverlap) {
  const CaseConfig c = load_case_from_string(sheared_gas(0.9), "le.toml");
  edmd::EdmdEngine<2> e(edmd::build_edmd_state(c));
  for (double t = 50.0; t <= 300.0; t += 50.0) {
    e.advance_to(t);
    EXPECT_GT(closest_pair(e.state().particles, t), 1.0 - 1e-9) << "t = " << t;
    const auto [slope, temperature] = shear_profile(e.state().particles);
    EXPECT_NEAR(slope, kRate, 0.05 * kRate) << "t = " << t;
    EXPECT_GT(temperature, 0.0);
  }
  EXPECT_GT(e.counters().collisions, 10000);
}

// Elastic discs cannot dissipate the work the shear does on them: viscous heating makes the
// temperature about the profile grow without bound (here several-fold between t = 50 and 300),
// whereas inelastic discs reach a steady temperature (same within 30% between t = 200 and 300: the
// fluctuations of a 400-disc system's temperature are about 5%).
TEST(EdmdLeesEdwards, ElasticDiscsHeatUpInelasticOnesReachASteadyState) {
  {
    const CaseConfig c = load_case_from_string(sheared_gas(1.0), "le.toml");
    edmd::EdmdEngine<2> e(edmd::build_edmd_state(c));
    e.advance_to(50.0);
    const double early = shear_profile(e.state().particles).second;
    e.advance_to(300.0);
    const double late = shear_profile(e.state().particles).second;
    EXPECT_GT(late, 3.0 * early);
  }
  {
    const CaseConfig c = load_case_from_string(sheared_gas(0.9), "le.toml");
    edmd::EdmdEngine<2> e(edmd::build_edmd_state(c));
    e.advance_to(200.0);
    const double early = shear_profile(e.state().particles).second;
    e.advance_to(300.0);
    const double late = shear_profile(e.state().particles).second;
    EXPECT_NEAR(late / early, 1.0, 0.3);
  }
}

// Strip profiles across the periodic seam: a disc straddling it counts at the other end as its
// image, moving with the boundary's velocity jump. Unbounded shear is homogeneous, so the two seam
// strips must show the interior's temperature and the linear profile's mean velocity. 30 strips of
// one diameter over t = 100-300 (every 1): a strip's temperature carries a block-averaged error of
// a few percent; 5 standard errors plus 3 % leaves no room for the seam's old error (a jump of
// U = 3 counted in, ten times the interior's temperature). Elastic discs heat up all the time, but
// alike everywhere, so the same holds for them.
TEST(EdmdLeesEdwards, SeamStripsEqualTheInterior) {
  for (const double restitution : {0.9, 1.0}) {
    const CaseConfig c = load_case_from_string(sheared_gas(restitution), "le.toml");
    edmd::EdmdEngine<2> e(edmd::build_edmd_state(c));
    observe::StripGrid grid(2, 1, 0.0, kSide, 30, kSide);
    grid.set_period(kSide, Vec3{kRate * kSide, 0.0, 0.0});
    observe::StripProfile profile(2, 30);
    e.advance_to(100.0);
    for (double t = 101.0; t <= 300.0; t += 1.0) {
      e.advance_to(t);
      profile.sample(e.state().particles, grid);
    }
    const auto strips = profile.averages();
    double interior = 0.0;
    for (int k = 2; k < 28; ++k) interior += strips[k].value[observe::strip::granular_temperature] / 26.0;
    for (const int k : {0, 29}) {
      const auto& a = strips[k];
      const double temperature = a.value[observe::strip::granular_temperature];
      EXPECT_NEAR(temperature, interior, 5.0 * a.error[observe::strip::granular_temperature] + 0.03 * interior)
          << "e = " << restitution << ", strip " << k;
      // The mean velocity follows the imposed profile u = rate (y - L/2) to its statistical error.
      EXPECT_NEAR(a.value[observe::strip::u], kRate * (a.centre - 0.5 * kSide), 5.0 * a.error[observe::strip::u] + 0.01)
          << "e = " << restitution << ", strip " << k;
    }
  }
}

// The images themselves (edmd/lees_edwards.hpp) against closed forms: the row above stands offset
// by U t modulo the width and moves at U; the nearest image of j may lie in the sliding row.
TEST(LeesEdwardsImages, TheOffsetIsUTModuloTheWidth) {
  const edmd::LeesEdwardsImages sheared{1.5};
  EXPECT_DOUBLE_EQ(sheared.offset(10.0, 2.0), 3.0);
  EXPECT_DOUBLE_EQ(sheared.offset(10.0, 9.0), 3.5);                        // 13.5 mod 10
  EXPECT_DOUBLE_EQ(edmd::LeesEdwardsImages{-1.5}.offset(10.0, 2.0), 7.0);  // within [0, L) either way
  EXPECT_EQ(edmd::LeesEdwardsImages{}.offset(10.0, 5.0), 0.0);
  EXPECT_FALSE(edmd::LeesEdwardsImages{}.sliding());
  EXPECT_TRUE(sheared.sliding());
}

TEST(LeesEdwardsImages, TheNearestImageMayLieInTheSlidingRow) {
  PeriodicBox box;
  box.hi = {10.0, 8.0, 6.0};
  box.periodic = {true, true, true};
  const edmd::LeesEdwardsImages sheared{1.5};
  const double t = 2.0;  // offset 3
  // j near the bottom, i near the top: j's image in the row above stands at (0.5 + 3, 0.5 + 8).
  const Vec3 xi{4.0, 7.5, 5.5}, xj{0.5, 0.5, 0.5};
  const Vec3 d = sheared.separation<3>(box, xi, xj, t);
  EXPECT_DOUBLE_EQ(d.x, 0.5);
  EXPECT_DOUBLE_EQ(d.y, -1.0);
  EXPECT_DOUBLE_EQ(d.z, -1.0);  // z wraps as in any periodic box
  // Seen from j the image of i lies in the row below, shifted back.
  const Vec3 back = sheared.separation<3>(box, xj, xi, t);
  EXPECT_DOUBLE_EQ(back.x, -0.5);
  EXPECT_DOUBLE_EQ(back.y, 1.0);
  // In 2D z is left alone; in one row the offset plays no part.
  EXPECT_DOUBLE_EQ(sheared.separation<2>(box, xi, xj, t).z, 5.0);
  const Vec3 same_row = sheared.separation<3>(box, {9.5, 4.0, 1.0}, {0.5, 3.0, 1.0}, t);
  EXPECT_DOUBLE_EQ(same_row.x, -1.0);
  EXPECT_DOUBLE_EQ(same_row.y, 1.0);
  // Not sliding: the plain minimum image.
  const Vec3 plain = edmd::LeesEdwardsImages{}.separation<3>(box, xi, xj, t);
  const Vec3 minimum = box.minimum_image(xi, xj);
  EXPECT_EQ(plain.x, minimum.x);
  EXPECT_EQ(plain.y, minimum.y);
  EXPECT_EQ(plain.z, minimum.z);
}

// The image in the row above moves at +U, that in the row below at -U; images across x move at a
// Couette cell's width rate, on top of the row's velocity.
TEST(LeesEdwardsImages, ImagesMoveWithTheirRowAndTheWidth) {
  PeriodicBox box;
  box.hi = {10.0, 8.0, 1.0};
  box.periodic = {true, true, true};
  const edmd::LeesEdwardsImages sheared{1.5};
  EXPECT_EQ(sheared.image_velocity(box, 0.0, {4.0, 7.5, 0.0}, {0.5, 0.5, 0.0}, 2.0).x, 1.5);
  EXPECT_EQ(sheared.image_velocity(box, 0.0, {0.5, 0.5, 0.0}, {4.0, 7.5, 0.0}, 2.0).x, -1.5);
  EXPECT_EQ(sheared.image_velocity(box, 0.0, {4.0, 4.0, 0.0}, {5.0, 3.0, 0.0}, 2.0).x, 0.0);
  const edmd::LeesEdwardsImages still;
  EXPECT_EQ(still.image_velocity(box, 0.2, {9.5, 4.0, 0.0}, {0.5, 4.0, 0.0}, 2.0).x, 0.2);  // j's image at 10.5
  EXPECT_EQ(still.image_velocity(box, 0.2, {0.5, 4.0, 0.0}, {9.5, 4.0, 0.0}, 2.0).x, -0.2);
  EXPECT_EQ(still.image_velocity(box, 0.2, {4.0, 4.0, 0.0}, {5.0, 4.0, 0.0}, 2.0).x, 0.0);
  // Both: j's image in the row above stands at x = 9.5 + 3 = 12.5; the one nearest i (at 2.0) is a
  // width back, at 2.5, and moves at U less the width rate.
  const Vec3 v = sheared.image_velocity(box, 0.2, {2.0, 7.5, 0.0}, {9.5, 0.5, 0.0}, 2.0);
  EXPECT_DOUBLE_EQ(v.x, 1.5 - 0.2);
  EXPECT_EQ(v.y, 0.0);
}

// A particle leaving through the top face enters the row above, which stands offset by U t and
// moves at U: brought back into the box it is shifted back by the offset (then into [lo, hi) along
// x) and slowed by U; through the bottom face the other way.
TEST(LeesEdwardsImages, AParticleThroughAYFaceBecomesItsImageInTheSlidingRow) {
  PeriodicBox box;
  box.hi = {10.0, 8.0, 1.0};
  box.periodic = {true, true, true};
  const edmd::LeesEdwardsImages sheared{1.5};
  Vec3 x{1.0, 0.0, 0.0}, v{0.7, 0.2, 0.0};                // y already brought down by a height
  EXPECT_EQ(sheared.enter_row(box, 1, 2.0, x, v), -1.0);  // 1 - 3 = -2, one width back up
  EXPECT_DOUBLE_EQ(x.x, 8.0);
  EXPECT_DOUBLE_EQ(v.x, 0.7 - 1.5);
  EXPECT_EQ(v.y, 0.2);
  Vec3 up{8.0, 8.0, 0.0}, w{0.0, -0.2, 0.0};               // through the bottom face
  EXPECT_EQ(sheared.enter_row(box, -1, 2.0, up, w), 1.0);  // 8 + 3 = 11
  EXPECT_DOUBLE_EQ(up.x, 1.0);
  EXPECT_DOUBLE_EQ(w.x, 1.5);
}
