// The HDF5 layer (src/grainflow/io/hdf5_file.hpp): growing datasets, fixed arrays and attributes
// read back exactly; the file appears under its name only when committed, and a writer destroyed
// without commit (a run that failed) leaves neither the file nor its temporary.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "grainflow/core/error.hpp"
#include "grainflow/io/hdf5_file.hpp"

using namespace grainflow;
namespace fs = std::filesystem;

namespace {
std::string scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "grainflow_hdf5_test";
  fs::create_directories(dir);
  fs::remove(dir / name);
  fs::remove(dir / (name + ".tmp"));
  return (dir / name).string();
}
}  // namespace

TEST(Hdf5File, GrowingDatasetsAndAttributesReadBackExactly) {
  const std::string path = scratch("roundtrip.h5");
  {
    io::H5Writer w(path);
    w.write("/id", std::vector<std::int64_t>{4, 7});
    w.attribute("/", "window", 5.93e-6);
    w.attribute("/", "samples", std::int64_t{3});
    w.attribute("/", "case", std::string("cases/x.toml"));
    w.group("/zones");
    w.write("/zones/edges", {0.0, 0.5, 1.0}, {3});
    auto time = w.growing("/time", {}, 2);
    auto velocity = w.growing("/velocity", {2, 3}, 2);
    for (int s = 0; s < 3; ++s) {
      const double t = 0.1 * s + 1.0 / 3.0;  // not exactly representable in decimal: tests the bits
      std::vector<double> row(6);
      for (int k = 0; k < 6; ++k) row[k] = s * 10 + k + 1e-17 * k;
      time.append(&t);
      velocity.append(row.data());
    }
    EXPECT_FALSE(fs::exists(path));  // still under its temporary name
    w.commit();
  }
  ASSERT_TRUE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  io::H5Reader r(path);
  EXPECT_TRUE(r.has("/velocity"));
  EXPECT_FALSE(r.has("/nothing"));
  EXPECT_EQ(r.number("/", "window"), 5.93e-6);
  EXPECT_EQ(r.number("/", "samples"), 3.0);
  EXPECT_EQ(r.text("/", "case"), "cases/x.toml");
  const auto v = r.read("/velocity");
  ASSERT_EQ(v.shape, (std::vector<unsigned long long>{3, 2, 3}));
  for (int s = 0; s < 3; ++s)
    for (int k = 0; k < 6; ++k) EXPECT_EQ(v.values[6 * s + k], s * 10 + k + 1e-17 * k);
  const auto t = r.read("/time");
  ASSERT_EQ(t.shape, (std::vector<unsigned long long>{3}));
  EXPECT_EQ(t.values[2], 0.2 + 1.0 / 3.0);
  EXPECT_EQ(r.read("/id").values, (std::vector<double>{4.0, 7.0}));
  EXPECT_EQ(r.read("/zones/edges").values, (std::vector<double>{0.0, 0.5, 1.0}));
}

TEST(Hdf5File, AnUncommittedWriterLeavesNothingBehind) {
  const std::string path = scratch("abandoned.h5");
  {
    io::H5Writer w(path);
    w.attribute("/", "window", 1.0);
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".tmp"));
}

TEST(Hdf5File, ReadingAMissingFileNamesIt) {
  try {
    io::H5Reader r("/nonexistent/dir/trajectory.h5");
    FAIL() << "opened a file that does not exist";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/trajectory.h5"), std::string::npos) << e.what();
  }
}
