// ZoneSeriesObserver (zone_series.h5): each zone's instantaneous mean velocity and the floor's
// motion on a fixed time grid; its own case table ([zone_series]) read, checked and written back
// through the schema it hands the case loader.
#include <gtest/gtest.h>

#include <string>

#include "grainflow/config/case_writer.hpp"
#include "grainflow/io/hdf5_file.hpp"
#include "grainflow/observe/zone_series_observer.hpp"
#include "observer_fixture.hpp"
#include "observer_table_checks.hpp"

namespace grainflow {
namespace {

struct ZoneSeriesCase : test::ObserverFixture {
  ZoneSeriesCase() {
    ObserverParameters& table = c.observer_tables.add("zone_series");
    table.set_number("start", 0.0);
    table.set_integer("samples", 3);
    table.set_number("interval", 1e-3);
    c.drive.enabled = true;
    c.drive.face = 2;
    // Zones are one diameter (1 mm) thick from y = 0: these spheres lie wholly in zones 0 and 2.
    add(1, {0.003, 0.0005, 0.005}, {0.1, 0.0, 0.0});
    add(2, {0.007, 0.0005, 0.005}, {0.1, 0.0, 0.0});
    add(3, {0.005, 0.0025, 0.005}, {0.0, -0.2, 0.05});
    add_wall(2, 0.0, {0.0, 0.3, 0.0});
  }
};

TEST(ZoneSeriesObserver, RecordsEachZonesMeanVelocityAndTheFloorOnItsGrid) {
  ZoneSeriesCase z;
  observe::ZoneSeriesObserver series(z.context(1e-4));
  // Due at 0, 1 and 2 ms (a step of 0.1 ms: the first step at or after each); 4 ms is past the
  // three samples asked for.
  for (long step = 0; step <= 40; ++step) {
    z.walls[0].position = 1e-5 * step;
    series.sample(z.at(step * 1e-4, step, 1e-4));
  }
  auto sink = z.sink();
  series.finish(sink);
  EXPECT_TRUE(z.warnings.empty());
  const io::H5Reader file((z.dir / "zone_series.h5").string());
  EXPECT_EQ(file.number("/", "samples"), 3.0);
  const io::H5Array time = file.read("/time");
  ASSERT_EQ(time.values.size(), 3u);
  EXPECT_NEAR(time.values[2], 2e-3, 1e-12);
  const io::H5Array u = file.read("/zone_velocity");
  ASSERT_EQ(u.shape.size(), 3u);
  const std::size_t zones = u.shape[1];
  EXPECT_EQ(zones, 10u);
  auto at = [&](std::size_t sample, std::size_t zone, int a) { return u.values[(sample * zones + zone) * 3 + a]; };
  EXPECT_NEAR(at(1, 0, 0), 0.1, 1e-12);
  EXPECT_NEAR(at(1, 2, 1), -0.2, 1e-12);
  EXPECT_NEAR(at(1, 2, 2), 0.05, 1e-12);
  EXPECT_EQ(at(1, 5, 0), 0.0);  // no mass there
  const io::H5Array floor = file.read("/floor_position");
  EXPECT_NEAR(floor.values[1], 1e-4, 1e-15);  // the wall's position at the 10th step
  EXPECT_NEAR(file.read("/floor_velocity").values[0], 0.3, 1e-15);
}

TEST(ZoneSeriesObserver, WarnsWhenTheRunEndsBeforeAllSamples) {
  ZoneSeriesCase z;
  z.c.observer_tables.add("zone_series").set_integer("samples", 5);
  observe::ZoneSeriesObserver series(z.context(1e-4));
  for (long step = 0; step <= 20; ++step) series.sample(z.at(step * 1e-4, step, 1e-4));
  auto sink = z.sink();
  series.finish(sink);
  ASSERT_EQ(z.warnings.size(), 1u);
  EXPECT_NE(z.warnings[0].find("3 of the 5"), std::string::npos) << z.warnings[0];
}

// Lan's spectra case, whose [zone_series] gives start and samples; the tests edit its samples line.
const std::string kSpectraCase = test::bundled_case("lan1994/sec4_3_spectra.toml");
const std::string kSamples = "samples = 2048";

TEST(ZoneSeriesObserver, ReadsItsOwnTableWithItsDefaults) {
  const CaseConfig c = test::load_edited_case(kSpectraCase, kSamples, kSamples);
  ASSERT_TRUE(c.observer_tables.has("zone_series"));
  const ObserverParameters& table = c.observer_tables.at("zone_series");
  EXPECT_EQ(table.number("start"), 15.0);
  EXPECT_EQ(table.integer("samples"), 2048);
  EXPECT_EQ(table.number("interval"), 0.0);  // 1 / (20 f) at run time
  // The case writer writes the table back as the observer stored it, and it reads back the same.
  const std::string written = write_case_toml(c);
  const std::string expected = "\n[zone_series]\nstart = 15.0\nsamples = 2048\ninterval = 0.0\n";
  EXPECT_NE(written.find(expected), std::string::npos) << written;
  EXPECT_EQ(load_case_from_string(written, kSpectraCase).observer_tables, c.observer_tables);
}

TEST(ZoneSeriesObserver, RefusesAnUnknownKeyOfItsTable) {
  test::expect_refused(kSpectraCase, kSamples, "samples = 2048\nwindow = 0.1", "zone_series.window", "unknown key");
}

TEST(ZoneSeriesObserver, RefusesBadValuesOfItsTableWithTheKeyAndReason) {
  test::expect_refused(kSpectraCase, kSamples, "samples = 8", "zone_series.samples", "needs at least 16 samples");
  test::expect_refused(kSpectraCase, kSamples, "samples = 2048\ninterval = -1.0", "zone_series.interval",
                       "must not be negative");
  // Its check against the run: an interval shorter than the time step.
  test::expect_refused(kSpectraCase, kSamples, "samples = 2048\ninterval = 1.0e-10", "zone_series.interval",
                       "is shorter than one time step");
}

}  // namespace
}  // namespace grainflow
