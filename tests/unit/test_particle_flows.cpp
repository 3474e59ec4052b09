// Particles entering and leaving a soft-sphere run: [[insertion]] places its particles clear of
// every particle and wall, by count or at its rate; [[outlet]] removes those whose centre enters
// it, counting them and their mass, and sends them back through an insertion when asked; the
// energy budget follows the particles present; the steady discharge rate of a cumulative mass;
// bad input refused naming the key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <variant>

#include "grainflow/core/error.hpp"
#include "grainflow/observe/discharge_observer.hpp"
#include "test_support.hpp"

using namespace grainflow;

namespace {

// A box 20 x 40 x 20 mm (open at the bottom face's outlet below y = 0), a cylinder post in it,
// glass spheres of 2 mm; `extra` adds tables.
std::string flow_case(const std::string& extra, int count = 0) {
  return "[domain]\nlo = [-0.01, -0.01, -0.01]\nhi = [0.01, 0.04, 0.01]\n"
         "boundary = { x = \"wall\", y = \"open\", z = \"wall\" }\n[gravity]\nvector = [0.0, -9.81, 0.0]\n"
         "[[species]]\nname = \"glass\"\ndiameter = 0.002\ndensity = 2500.0\ncount = " +
         std::to_string(count) +
         "\n[particles]\ninit = \"random\"\nregion_lo = [-0.009, 0.02, -0.009]\nregion_hi = [0.009, 0.038, 0.009]\n"
         "[contact]\nmodel = \"linear_dashpot\"\nkn = 1.0e4\ngamma_n = 2.0e3\nfriction = 0.3\n"
         "[[geometry]]\nname = \"post\"\ntype = \"cylinder\"\npoint = [0.0, 0.0, 0.0]\naxis = [0.0, 1.0, 0.0]\n"
         "radius = 0.003\ninside = false\n" +
         extra + "[run]\nduration = 1.0\ntime_step = 2.0e-6\n";
}

// Every pair apart, every particle in the region and clear of the box's side walls and the post.
void expect_clear(const ParticleStore& p, const Vec3& lo, const Vec3& hi) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vec3 x = p.position[i];
    const double r = p.radius[i];
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(x[a], lo[a]);
      EXPECT_LE(x[a], hi[a]);
    }
    EXPECT_GE(std::hypot(x.x, x.z), 0.003 + r * (1.0 - 1e-12)) << "inside the post";
    EXPECT_GE(x.x - r, -0.01 - 1e-15);
    EXPECT_LE(x.x + r, 0.01 + 1e-15);
    for (std::size_t j = i + 1; j < p.size(); ++j) EXPECT_GE(norm(x - p.position[j]), r + p.radius[j] - 1e-15);
  }
}

TEST(ParticleFlows, InsertionByCountPlacesThemClearOfEverythingOnce) {
  auto engine = test::engine_from_toml(
      flow_case("[[insertion]]\nname = \"feed\"\nspecies = \"glass\"\ncount = 60\nregion_lo = [-0.01, 0.01, -0.01]\n"
                "region_hi = [0.01, 0.03, 0.01]\nvelocity = [0.0, -0.1, 0.0]\nstart = 0.0\n"),
      testing::TempDir() + "insert.toml", 1);
  std::visit(
      [&](auto& e) {
        EXPECT_EQ(e.state().particles.size(), 0u);
        for (int k = 0; k < 25; ++k) e.step();  // the first exchange comes at a rebuild within 20 steps
        const ParticleStore& p = e.state().particles;
        ASSERT_EQ(p.size(), 60u) << "60 spheres of 2 mm fill 6 % of the 8 cm^3 region: every one finds room";
        expect_clear(p, {-0.01, 0.01, -0.01}, {0.01, 0.03, 0.01});
        std::set<std::uint32_t> ids(p.id.begin(), p.id.end());
        EXPECT_EQ(ids.size(), 60u);
        for (std::size_t i = 0; i < p.size(); ++i) EXPECT_NEAR(p.velocity[i].y, -0.1, 25 * 2e-6 * 9.81 + 1e-12);
        for (int k = 0; k < 2000; ++k) e.step();
        EXPECT_EQ(e.state().particles.size(), 60u) << "a count is put in once";
      },
      engine);
}

// At 2000 per second from t = 1 ms on, floor(2000 (t - 0.001)) particles have been made by time t;
// an exchange every 20 steps (40 us, 0.08 particles' worth) places them, so at t = 0.021 s there are
// 40, one fewer when the last waits for the next exchange, one more fewer when the clock's
// rounding puts 2000 (t - 0.001) just below 40.
TEST(ParticleFlows, InsertionByRateFollowsItsRate) {
  auto engine = test::engine_from_toml(
      flow_case("[[insertion]]\nname = \"feed\"\nspecies = \"glass\"\nrate = 2000.0\nregion_lo = [-0.01, 0.01, -0.01]\n"
                "region_hi = [0.01, 0.03, 0.01]\nstart = 0.001\n"),
      testing::TempDir() + "rate.toml", 1);
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < 10500; ++k) e.step();  // t = 0.021 s
        const std::size_t n = e.state().particles.size();
        EXPECT_TRUE(n >= 38u && n <= 40u) << n;
        EXPECT_EQ(e.waiting_count(), 0u);
      },
      engine);
}

// 40 spheres fall through the open bottom into an outlet below y = -2 mm: each is removed once,
// with its mass; then, with the outlet sending them back to the top, the count stays at 40 and
// they keep flowing. The energy budget follows the particles present: its residual stays at the
// integrator's level (1e-3 of the input here at most; with a removal uncounted it would be of the
// order of the removed energy, ~1).
TEST(ParticleFlows, AnOutletRemovesCountsAndReinserts) {
  const std::string outlet =
      "[[outlet]]\nname = \"drain\"\nregion_lo = [-0.01, -0.01, -0.01]\nregion_hi = [0.01, -0.002, 0.01]\n";
  auto engine = test::engine_from_toml(flow_case(outlet, 40), testing::TempDir() + "outlet.toml", 1);
  std::visit(
      [&](auto& e) {
        const double mass = e.state().particles.mass[0];
        std::vector<typename std::decay_t<decltype(e)>::Removed> removed;  // each exchange's, taken after it
        for (int k = 0; k < 60000; ++k) {                                  // 0.12 s: a fall of 4 cm takes 0.09 s
          e.step();
          for (auto& r : e.take_removed()) removed.push_back(r);
        }
        ASSERT_EQ(e.outlet_counts().size(), 1u);
        EXPECT_EQ(e.outlet_counts()[0].removed + static_cast<long>(e.state().particles.size()), 40);
        EXPECT_GT(e.outlet_counts()[0].removed, 30);
        EXPECT_NEAR(e.outlet_counts()[0].mass, mass * e.outlet_counts()[0].removed, 1e-12 * mass);
        EXPECT_EQ(static_cast<long>(removed.size()), e.outlet_counts()[0].removed);
        for (const auto& r : removed) EXPECT_LE(r.particle.position.y, -0.002);
        const auto budget = e.energy_budget();
        EXPECT_LT(std::fabs(budget.residual(1.0)), 1e-3);
      },
      engine);
  auto loop = test::engine_from_toml(
      flow_case("[[insertion]]\nname = \"top\"\nspecies = \"glass\"\ncount = 0\nregion_lo = [-0.01, 0.025, -0.01]\n"
                "region_hi = [0.01, 0.04, 0.01]\n" +
                    outlet + "reinsert = \"top\"\n",
                40),
      testing::TempDir() + "loop.toml", 1);
  std::visit(
      [&](auto& e) {
        for (int k = 0; k < 150000; ++k) e.step();  // 0.3 s: each sphere falls through ~2-3 times
        EXPECT_GT(e.outlet_counts()[0].removed, 80);
        EXPECT_EQ(e.state().particles.size() + e.waiting_count(), 40u);
        std::set<std::uint32_t> ids(e.state().particles.id.begin(), e.state().particles.id.end());
        EXPECT_EQ(ids.size(), e.state().particles.size()) << "a particle comes back under its own id";
        EXPECT_LT(*ids.rbegin(), 40u);
        EXPECT_LT(std::fabs(e.energy_budget().residual(1.0)), 1e-3);
      },
      loop);
}

// M(t) = 2 (t - 1) after a start-up at rest: the slope over the 20-80 % window is 2 exactly and
// every block's rate is 2 (error 0); with alternating noise of +-0.01 kg the error is small but
// not zero.
TEST(ParticleFlows, SteadyDischargeRateIsTheSlopeOverTheMiddleWindow) {
  std::vector<double> t, m;
  for (int k = 0; k <= 200; ++k) {
    t.push_back(0.05 * k);
    m.push_back(std::max(0.0, 2.0 * (t.back() - 1.0)));
  }
  auto d = observe::steady_discharge_rate(t, m);
  ASSERT_TRUE(d.measured);
  EXPECT_NEAR(d.rate, 2.0, 1e-12);
  EXPECT_NEAR(d.error, 0.0, 1e-9);
  EXPECT_NEAR(d.start, 2.8, 0.05 + 1e-12);  // 20 % of M(10) = 18 is reached at t = 1 + 3.6 / 2
  EXPECT_NEAR(d.end, 8.2, 0.05 + 1e-12);    // and 80 % at 1 + 14.4 / 2
  for (std::size_t k = 0; k < m.size(); ++k) m[k] += (k % 2 ? 0.01 : -0.01);
  d = observe::steady_discharge_rate(t, m);
  EXPECT_NEAR(d.rate, 2.0, 0.01);
  EXPECT_GT(d.error, 0.0);
  EXPECT_LT(d.error, 0.1);
}

std::string refusal(const std::string& text) {
  try {
    auto engine = test::engine_from_toml(text, testing::TempDir() + "bad_flow.toml", 1);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(accepted)";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ParticleFlows, BadFlowsAreRefusedNamingTheKey) {
  const std::string feed = "[[insertion]]\nname = \"feed\"\nspecies = \"glass\"\n";
  const std::string box = "region_lo = [-0.01, 0.01, -0.01]\nregion_hi = [0.01, 0.03, 0.01]\n";
  EXPECT_EQ(refusal(flow_case(feed + "count = 5\n" + box)), "(accepted)");
  EXPECT_PRED2(contains, refusal(flow_case(feed + "count = 5\nrate = 3.0\n" + box)), "insertion.0.count");
  EXPECT_PRED2(contains, refusal(flow_case("[[insertion]]\nname = \"feed\"\nspecies = \"sand\"\ncount = 5\n" + box)),
               "insertion.0.species");
  EXPECT_PRED2(
      contains,
      refusal(flow_case(feed + "count = 5\nregion_lo = [-0.01, 0.01, -0.01]\nregion_hi = [0.01, 0.05, 0.01]\n")),
      "reaches outside the box");
  EXPECT_PRED2(
      contains,
      refusal(flow_case(feed + "count = 5\nregion_lo = [-0.001, 0.01, -0.001]\nregion_hi = [0.001, 0.03, 0.001]\n")),
      "lies inside a wall");
  // 20 mm of fall from rest takes 64 ms; the region holds ~0.3 x 8e-6 / 4.2e-9 = 573: at most ~9000/s.
  EXPECT_PRED2(contains, refusal(flow_case(feed + "rate = 50000.0\n" + box)), "insertion.0.rate");
  EXPECT_EQ(refusal(flow_case(feed + "rate = 5000.0\n" + box)), "(accepted)");
  EXPECT_PRED2(contains, refusal(flow_case(feed + "count = 5\ninside = \"silo\"\n")), "insertion.0.inside");
  EXPECT_PRED2(contains,
               refusal(flow_case("[[outlet]]\nname = \"drain\"\nregion_lo = [-0.01, -0.05, -0.01]\n"
                                 "region_hi = [0.01, -0.02, 0.01]\n",
                                 4)),
               "no particle can reach it");
  EXPECT_PRED2(contains,
               refusal(flow_case("[[outlet]]\nname = \"drain\"\nregion_lo = [-0.01, -0.01, -0.01]\n"
                                 "region_hi = [0.01, -0.002, 0.01]\nreinsert = \"nowhere\"\n")),
               "outlet.0.reinsert");
  EXPECT_PRED2(contains,
               refusal(flow_case("[[outlet]]\nname = \"drain\"\nregion_lo = [0.01, -0.01, -0.01]\n"
                                 "region_hi = [-0.01, -0.002, 0.01]\n")),
               "outlet.0.region_hi");
}

}  // namespace
