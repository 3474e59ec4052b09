// GeometryObserver (geometry.csv): one row per output time and geometry with the loads the frame
// reports, the t = 0 row of a fresh run first, on the output.interval grid.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "grainflow/observe/geometry_observer.hpp"
#include "observer_fixture.hpp"

namespace grainflow {
namespace {

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(GeometryObserver, WritesEachGeometrysLoadAtTheOutputTimes) {
  test::ObserverFixture f;
  f.c.output.interval = 0.01;
  f.c.geometry.resize(2);
  f.c.geometry[0].name = "drum";
  f.c.geometry[1].name = "lid";
  const double dt = 0.001;
  observe::GeometryObserver o(f.context(dt));
  double scale = 1.0;  // the loads change with time, to tell the samples apart
  f.frame.geometry_loads = [&] {
    return std::vector<observe::GeometryLoad>{{"drum", {1.0 * scale, -2.0 * scale, 0.0}, {0.0, 0.0, 0.5 * scale}},
                                              {"lid", {0.0, 3.0, 0.0}, {-1.0, 0.0, 0.0}}};
  };
  o.sample_start(f.at(0.0));
  for (long step = 1; step <= 25; ++step) {
    scale = 1.0 + step;
    o.sample(f.at(step * dt, step, dt));
  }
  auto sink = f.sink();
  o.write(f.at(25 * dt, 25, dt), sink);
  const auto lines = lines_of((f.dir / "geometry.csv").string());
  ASSERT_EQ(lines.size(), 2u + 3u * 2u);  // t = 0, 0.01, 0.02, two geometries each
  EXPECT_EQ(lines[0].rfind("# units:", 0), 0u);
  EXPECT_EQ(lines[1], "time,name,force_x,force_y,force_z,torque_x,torque_y,torque_z");
  EXPECT_EQ(lines[2], "0,drum,1,-2,0,0,0,0.5");
  EXPECT_EQ(lines[3], "0,lid,0,3,0,-1,0,0");
  EXPECT_EQ(lines[4], "0.01,drum,11,-22,0,0,0,5.5");  // step 10
  EXPECT_EQ(lines[7], "0.02,lid,0,3,0,-1,0,0");
}

TEST(GeometryObserver, SumsTheRanksShares) {
  test::ObserverFixture f;
  f.c.output.interval = 0.01;
  f.c.geometry.resize(1);
  f.c.geometry[0].name = "drum";
  observe::RunContext run = f.context(0.01);
  run.ranks.sum_in_place = [](double* v, std::size_t n) {  // two ranks holding the same share
    for (std::size_t k = 0; k < n; ++k) v[k] *= 2.0;
  };
  observe::GeometryObserver o(run);
  f.frame.geometry_loads = [] { return std::vector<observe::GeometryLoad>{{"drum", {0.0, 1.5, 0.0}, {}}}; };
  o.sample(f.at(0.01, 1, 0.01));
  ASSERT_EQ(o.values().size(), 7u);
  EXPECT_DOUBLE_EQ(o.values()[0], 0.01);  // the time is not summed
  EXPECT_DOUBLE_EQ(o.values()[2], 3.0);
}

TEST(GeometryObserver, WritesNothingWithoutGeometry) {
  test::ObserverFixture f;
  f.c.output.interval = 0.01;
  observe::GeometryObserver o(f.context(0.01));
  o.sample(f.at(0.01, 1, 0.01));
  auto sink = f.sink();
  o.write(f.at(0.01, 1, 0.01), sink);
  EXPECT_FALSE(std::filesystem::exists(f.dir / "geometry.csv"));
}

}  // namespace
}  // namespace grainflow
