// write_vtp (snapshots of [[geometry]] walls) and the walls particles.pvd lists beside the particles:
// the PolyData holds the points and triangles it was given, and the index names each part's file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "grainflow/io/vtp_writer.hpp"
#include "grainflow/io/vtu_writer.hpp"

namespace grainflow {
namespace {

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream all;
  all << in.rdbuf();
  return all.str();
}

// The numbers of the DataArray named `name` (the first after it).
std::vector<double> array_of(const std::string& xml, const std::string& name) {
  const std::size_t at = xml.find("Name=\"" + name + "\"");
  EXPECT_NE(at, std::string::npos) << name;
  const std::size_t begin = xml.find('>', at) + 1;
  std::stringstream numbers(xml.substr(begin, xml.find('<', begin) - begin));
  std::vector<double> values;
  for (double v; numbers >> v;) values.push_back(v);
  return values;
}

std::filesystem::path temp_dir(const std::string& what) {
  auto dir = std::filesystem::path(testing::TempDir()) / ("grainflow_" + what + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(VtpWriter, WritesThePointsAndTrianglesItIsGiven) {
  const auto dir = temp_dir("vtp");
  const std::vector<Vec3> points = {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {1.0, 2.0, 0.0}, {0.0, 2.0, 0.125}};
  const std::vector<std::array<int, 3>> triangles = {{0, 1, 2}, {0, 2, 3}};
  io::write_vtp((dir / "wall.vtp").string(), points, triangles);
  const std::string xml = slurp(dir / "wall.vtp");
  EXPECT_NE(xml.find("type=\"PolyData\""), std::string::npos);
  EXPECT_NE(xml.find("NumberOfPoints=\"4\""), std::string::npos);
  EXPECT_NE(xml.find("NumberOfPolys=\"2\""), std::string::npos);
  const auto position = array_of(xml, "position");
  ASSERT_EQ(position.size(), 12u);
  EXPECT_DOUBLE_EQ(position[7], 2.0);     // point 2's y
  EXPECT_DOUBLE_EQ(position[11], 0.125);  // point 3's z
  EXPECT_EQ(array_of(xml, "connectivity"), (std::vector<double>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(array_of(xml, "offsets"), (std::vector<double>{3, 6}));
  std::filesystem::remove_all(dir);
}

TEST(VtpWriter, ParticlesPvdListsEachWallAsAPartAtEveryTime) {
  const auto dir = temp_dir("pvd_parts");
  io::PvdSeries series(dir.string());
  series.set_parts({{"drum", false}, {"paddle", true}});
  ParticleStore none;
  series.add(none, 0.0);
  series.add(none, 5.0);
  const std::string pvd = slurp(dir / "particles.pvd");
  EXPECT_NE(pvd.find("timestep=\"5\" group=\"\" part=\"0\" file=\"particles_000001.vtu\""), std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"0\" group=\"\" part=\"1\" file=\"drum.vtp\""), std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"5\" group=\"\" part=\"1\" file=\"drum.vtp\""), std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"5\" group=\"\" part=\"2\" file=\"paddle_000001.vtp\""), std::string::npos);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace grainflow
