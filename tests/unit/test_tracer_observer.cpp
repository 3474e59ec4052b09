// TracerObserver (tracers.csv): the rows it writes for the particles it follows, on its own time grid.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "grainflow/observe/tracer_observer.hpp"
#include "observer_fixture.hpp"

namespace grainflow {
namespace {

std::vector<std::vector<std::string>> rows_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("time,", 0) == 0) continue;
    std::vector<std::string> cells;
    std::stringstream cells_of(line);
    for (std::string cell; std::getline(cells_of, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

struct TracerCase : test::ObserverFixture {
  TracerCase() {
    c.tracers.enabled = true;
    c.tracers.particles = {9};
    SpeciesConfig intruder = c.species.front();
    intruder.name = "intruder";
    c.species.push_back(intruder);
    c.tracers.species = {"intruder"};
    c.tracers.interval = 0.01;
    c.drive.enabled = true;  // the floor's motion goes beside every row
    c.drive.face = 2;
    add(9, {0.002, 0.003, 0.004}, {1.0, 2.0, 3.0});
    add(4, {0.005, 0.005, 0.005}, {0.0, 0.0, 0.0});      // not followed
    add(7, {0.006, 0.007, 0.008}, {-1.0, 0.0, 0.5}, 1);  // an intruder
    particles.image[0] = {2, 0, -1};                     // crossed +x twice and -z once
    add_wall(2, 0.0005, {0.0, 0.1, 0.0});
    frame.coordination = [this] {
      std::vector<engine_api::Coordination> touch(particles.size());
      touch[0] = {4, 1};
      touch[2] = {6, 0};
      return touch;
    };
  }
};

TEST(TracerObserver, FollowsNamedParticlesAndSpeciesWithUnwrappedPositions) {
  TracerCase t;
  observe::TracerObserver tracers(t.context(1e-4), t.particles);
  EXPECT_EQ(tracers.ids(), (std::vector<std::uint32_t>{7, 9}));
  for (double time : {0.0, 0.005, 0.01}) tracers.sample(t.at(time, 0, 1e-4));  // due at 0 and 0.01 only
  auto sink = t.sink();
  tracers.write(t.frame, sink);
  const auto rows = rows_of((t.dir / "tracers.csv").string());
  ASSERT_EQ(rows.size(), 4u);  // two samples of two particles, by time then id
  EXPECT_EQ(rows[0][1], "7");
  EXPECT_EQ(rows[1][1], "9");
  EXPECT_EQ(rows[2][0], "0.01");
  // x + image L: 0.002 + 2 (0.01) and 0.004 - 0.01, the velocity, coordination and the floor.
  const auto& r = rows[1];
  EXPECT_DOUBLE_EQ(std::stod(r[2]), 0.022);
  EXPECT_DOUBLE_EQ(std::stod(r[3]), 0.003);
  EXPECT_DOUBLE_EQ(std::stod(r[4]), -0.006);
  EXPECT_EQ(r[5] + "," + r[6] + "," + r[7], "1,2,3");
  EXPECT_EQ(r[8], "4");
  EXPECT_EQ(r[9], "1");
  EXPECT_DOUBLE_EQ(std::stod(r[10]), 0.0005);
  EXPECT_DOUBLE_EQ(std::stod(r[11]), 0.1);
  EXPECT_EQ(rows[0][8], "6");
}

TEST(TracerObserver, CheckpointCarriesTheRowsAndTheGrid) {
  TracerCase t;
  observe::TracerObserver before(t.context(1e-4), t.particles);
  before.sample(t.at(0.0, 0, 1e-4));
  io::StateArchive out = io::StateArchive::for_writing();
  before.serialize(out);

  observe::TracerObserver after(t.context(1e-4), t.particles);
  io::StateArchive in = io::StateArchive::for_reading(out.bytes(), "test");
  after.serialize(in);
  in.expect_end();
  after.sample(t.at(0.005, 0, 1e-4));  // the restored grid: next sample at 0.01, not now
  after.sample(t.at(0.01, 0, 1e-4));
  auto sink = t.sink();
  after.write(t.frame, sink);
  EXPECT_EQ(rows_of((t.dir / "tracers.csv").string()).size(), 4u);
}

}  // namespace
}  // namespace grainflow
