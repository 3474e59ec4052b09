// ConvectionObserver's own case table ([field]): read with its defaults, written back by the case
// writer, and refused with the file, the key and the reason, through the schema it hands the case
// loader.
#include <gtest/gtest.h>

#include <string>

#include "grainflow/config/case_writer.hpp"
#include "grainflow/observe/convection_observer.hpp"
#include "observer_table_checks.hpp"

namespace grainflow {
namespace {

// Lan's convection cell, whose [field] gives axis and phase_bins; the tests edit its phase_bins line.
const std::string kCellCase = test::bundled_case("lan1994/sec5_1_3_cell_20dx3d.toml");
const std::string kBins = "phase_bins = 8";

TEST(ConvectionObserver, ReadsItsOwnTableWithItsDefaults) {
  const CaseConfig c = test::load_edited_case(kCellCase, kBins, kBins);
  ASSERT_TRUE(c.observer_tables.has(observe::ConvectionObserver::table.table));
  const ObserverParameters& table = c.observer_tables.at("field");
  EXPECT_EQ(table.text("axis"), "z");
  EXPECT_EQ(table.number("cell"), 0.0);  // one reference diameter at run time
  EXPECT_FALSE(table.has("start"));      // output.average_start at run time
  EXPECT_EQ(table.number("interval"), 0.0);
  EXPECT_EQ(table.integer("phase_bins"), 8);
  const std::string written = write_case_toml(c);
  const std::string expected = "\n[field]\naxis = \"z\"\ncell = 0.0\ninterval = 0.0\nphase_bins = 8\n";
  EXPECT_NE(written.find(expected), std::string::npos) << written;
  EXPECT_EQ(load_case_from_string(written, kCellCase).observer_tables, c.observer_tables);
}

TEST(ConvectionObserver, RefusesAnUnknownKeyOfItsTable) {
  test::expect_refused(kCellCase, kBins, "phase_bins = 8\nbins = 4", "field.bins", "unknown key");
}

TEST(ConvectionObserver, RefusesBadValuesOfItsTableWithTheKeyAndReason) {
  test::expect_refused(kCellCase, kBins, "phase_bins = 361", "field.phase_bins", "must lie in [0, 360]");
  test::expect_refused(kCellCase, kBins, "phase_bins = 8\ncell = -0.001", "field.cell", "must not be negative");
  // Its checks against the run: the plane's horizontal axis is not gravity's, cells not too small.
  test::expect_refused(kCellCase, "axis = \"z\"", "axis = \"y\"", "field.axis", "it is the gravity axis");
  test::expect_refused(kCellCase, kBins, "phase_bins = 8\ncell = 1.0e-6", "field.cell", "under a tenth of a diameter");
}

}  // namespace
}  // namespace grainflow
