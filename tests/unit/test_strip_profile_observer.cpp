// StripProfileObserver: Campbell's strip profiles of an event-driven run, and the per-run S his
// listing averages over the strips (COL002's "AVERAGE R").
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "grainflow/observe/strip_profile_observer.hpp"
#include "observer_fixture.hpp"

namespace grainflow {
namespace {

// A Couette cell 10 mm tall (walls at ylo and yhi, periodic along x and z), averaging from
// `average_start`.
void make_couette_cell(test::ObserverFixture& f, double average_start) {
  f.c.output.average_start = average_start;
  f.c.output.interval = 1.0;
  f.box.periodic = {true, false, true};
  f.add_wall(2, 0.0);
  f.add_wall(3, 0.01);
}

// A Couette cell 10 mm tall with 1 mm discs' worth of strips: in strip k two spheres at its centre
// move at u = shear y +- delta_k and v = -+ delta_k, so each strip's mean u is shear y, and
// <u'^2> = <v'^2> = delta_k^2: S_listing = 2R (du/dy) / sqrt(2 delta_k^2). delta_k grows with k, so
// the mean over the strips (the listing's) and the middle strip's S differ by ~30 %.
TEST(StripProfileObserver, SavageJeffreySOfEachStripAndTheirMean) {
  test::ObserverFixture f;
  make_couette_cell(f, 0.0);
  const double shear = 50.0;                                   // 1/s
  auto delta = [](int k) { return 0.005 * (1.0 + 0.5 * k); };  // m/s
  std::uint32_t id = 0;
  double mean = 0.0;
  for (int k = 0; k < 10; ++k) {
    const double y = (k + 0.5) * 1e-3;
    f.add(id++, {0.002, y, 0.005}, {shear * y + delta(k), -delta(k), 0.0});
    f.add(id++, {0.007, y, 0.005}, {shear * y - delta(k), delta(k), 0.0});
    mean += 2.0 * 0.5e-3 * shear / std::sqrt(2.0 * delta(k) * delta(k)) / 10.0;
  }
  const observe::RunContext run = f.context(0.0);
  observe::StripProfileObserver profiles(run, f.at(0.0));
  profiles.sample(f.at(0.1));
  profiles.sample(f.at(0.2));
  auto sink = f.sink();
  profiles.write(f.frame, sink);
  std::ostringstream json;
  f.summary.write(json);
  const std::string text = json.str();
  const double middle = 2.0 * 0.5e-3 * shear / std::sqrt(2.0 * delta(5) * delta(5));
  ASSERT_GT(std::abs(mean / middle - 1.0), 0.1);  // the two readings are told apart
  for (auto [key, expected] :
       {std::pair{"\"S_listing_strip_mean\": ", mean}, std::pair{"\"S_listing_middle_strip\": ", middle}}) {
    const auto at = text.find(key);
    ASSERT_NE(at, std::string::npos) << key << " missing in " << text;
    EXPECT_NEAR(std::stod(text.substr(at + std::string(key).size())), expected, 1e-9 * expected) << key;
  }
}

// A run reads when the long-term averages began through the Observer interface, not the concrete
// type: NaN before the first sample, then its time; an observer that keeps no averages says NaN.
TEST(StripProfileObserver, TellsARunThroughTheObserverInterfaceWhenItsAveragesBegan) {
  test::ObserverFixture f;
  make_couette_cell(f, 0.05);
  f.add(0, {0.002, 0.005, 0.005}, {0.1, 0.0, 0.0});
  const observe::RunContext run = f.context(0.0);
  observe::StripProfileObserver profiles(run, f.at(0.0));
  const observe::Observer& seen = profiles;
  EXPECT_TRUE(std::isnan(seen.first_sample_time()));
  profiles.sample(f.at(0.1));
  profiles.sample(f.at(0.2));
  EXPECT_EQ(seen.first_sample_time(), 0.1);

  struct NoAverages final : observe::Observer {
    std::string name() const override { return "none"; }
    void sample(const observe::Frame&) override {}
    void serialize(io::StateArchive&) override {}
  } none;
  EXPECT_TRUE(std::isnan(static_cast<const observe::Observer&>(none).first_sample_time()));
}

// Unbounded simple shear (Lees-Edwards, periodic along y): rows of spheres every quarter diameter
// move exactly on the imposed profile u = shear (y - H/2). The arrangement repeats every strip, so
// every strip, the two at the seam included, must have the same spread of u (the profile's own
// variation across a strip) and the mean u of its centre. A sphere straddling the seam counts in
// the strips at the other end as its image, which moves at u + shear H (above) or u - shear H
// (below); counted with its own velocity it would add a jump of shear H to those strips.
TEST(StripProfileObserver, LeesEdwardsSeamStripsEqualTheInterior) {
  test::ObserverFixture f;
  f.c.output.average_start = 0.0;
  f.c.output.interval = 1.0;
  const double shear = 50.0, height = 0.01;  // 1/s, m
  f.c.lees_edwards_rate = shear;
  f.box.periodic = {true, true, true};
  std::uint32_t id = 0;
  for (int row = 0; row < 40; ++row) {
    const double y = (row + 0.5) * 0.25e-3;
    f.add(id++, {0.001 + 0.2e-3 * row, y, 0.005}, {shear * (y - 0.5 * height), 0.0, 0.0});
  }
  const observe::RunContext run = f.context(0.0);
  observe::StripProfileObserver profiles(run, f.at(0.0));
  profiles.sample(f.at(0.1));
  const auto strips = profiles.strip_kinematics();
  ASSERT_EQ(strips.size(), 10u);
  const double spread = strips[5].averages.value[observe::strip::u_variance];
  EXPECT_GT(spread, 0.0);
  for (std::size_t k = 0; k < strips.size(); ++k) {
    const auto& a = strips[k].averages;
    // Round-off of sums of ~10 shares of speeds up to shear H/2 = 0.25 m/s.
    EXPECT_NEAR(a.value[observe::strip::u], shear * (a.centre - 0.5 * height), 1e-12) << "strip " << k;
    EXPECT_NEAR(a.value[observe::strip::u_variance], spread, 1e-9 * spread) << "strip " << k;
    EXPECT_NEAR(a.value[observe::strip::temperature_lan], strips[5].averages.value[observe::strip::temperature_lan],
                1e-9 * spread)
        << "strip " << k;
    EXPECT_NEAR(a.value[observe::strip::solids_fraction], strips[5].averages.value[observe::strip::solids_fraction],
                1e-12)
        << "strip " << k;
  }
}

}  // namespace
}  // namespace grainflow
