// ContactStressObserver (a soft-sphere run's stresses.csv and walls.csv): each contact force shared
// among the strips along its branch vector by length, wall contacts from the contact point, the
// kinetic part about the strip's mean velocity, all per unit strip volume and averaged over time;
// the wall's load per unit area. Hand-made forces, so every value has a closed form.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "grainflow/observe/contact_stress_observer.hpp"
#include "observer_fixture.hpp"

namespace grainflow {
namespace {

std::vector<std::map<std::string, double>> read_rows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> names;
  std::vector<std::map<std::string, double>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::stringstream cells(line);
    std::vector<std::string> values;
    for (std::string cell; std::getline(cells, cell, ',');) values.push_back(cell);
    if (names.empty()) {
      names = values;
      continue;
    }
    std::map<std::string, double> row;
    for (std::size_t k = 0; k < names.size(); ++k) row[names[k]] = std::strtod(values[k].c_str(), nullptr);
    rows.push_back(row);
  }
  return rows;
}

// Particle 1 rests on the floor (y = 0.5 mm), particle 0 on it (y = 1.5 mm), particle 2 beside
// particle 0 in the same strip; strips 1 mm thick over a 10 x 10 mm cross-section (1e-7 m^3).
struct StackedPair : test::ObserverFixture {
  static constexpr double kVolume = 1e-7, kArea = 1e-4;
  Vec3 pair_force{0.2e-3, 1.0e-3, 0.0};    // N on particle 0 from particle 1
  Vec3 floor_force{-0.1e-3, 3.0e-3, 0.0};  // N on particle 1 from the floor
  StackedPair() {
    c.output.profile_interval = 0.01;
    c.output.average_start = 0.0;
    add(0, {0.005, 0.0015, 0.005}, {1.0, 0.0, 0.0});
    add(1, {0.005, 0.0005, 0.005}, {0.0, 0.0, 0.0});
    add(2, {0.002, 0.0015, 0.005}, {-1.0, 0.0, 0.0});
    add_wall(2, 0.0);
    frame.contact_forces = [this](const observe::Frame::ContactForceVisit& visit) {
      visit(0, -1, particles.position[1], pair_force);
      visit(1, 0, Vec3{0.005, 0.0, 0.005}, floor_force);
    };
  }
};

TEST(ContactStressObserver, SharesEachBranchAmongTheStripsItCrosses) {
  StackedPair t;
  const double dt = 1e-3;
  observe::ContactStressObserver stresses(t.context(dt), t.at(0.0, 0, dt));
  for (long step = 1; step <= 30; ++step) stresses.sample(t.at(step * dt, step, dt));  // due at 10, 20, 30
  auto sink = t.sink();
  stresses.write(t.frame, sink);
  const auto strips = read_rows((t.dir / "stresses.csv").string());
  ASSERT_EQ(strips.size(), 10u);
  // Strip 0 holds half the pair's 1 mm branch and the whole floor branch (0.5 mm); strip 1 the other
  // half of the pair's. P_ab = sum share * branch_a * force_b / volume; branch along +y only.
  const double half = 0.5e-3;
  EXPECT_NEAR(strips[0].at("contact_yy"), (half * t.pair_force.y + half * t.floor_force.y) / t.kVolume, 1e-9);
  EXPECT_NEAR(strips[0].at("contact_yx"), (half * t.pair_force.x + half * t.floor_force.x) / t.kVolume, 1e-9);
  EXPECT_NEAR(strips[1].at("contact_yy"), half * t.pair_force.y / t.kVolume, 1e-9);
  EXPECT_NEAR(strips[1].at("contact_yx"), half * t.pair_force.x / t.kVolume, 1e-9);
  EXPECT_EQ(strips[1].at("contact_xx"), 0.0);  // no branch along x
  EXPECT_EQ(strips[2].at("contact_yy"), 0.0);
  // Kinetic: particles 0 and 2 (1e-6 kg, +-1 m/s along x) about their strip's mean 0.
  EXPECT_NEAR(strips[1].at("kinetic_xx"), 2.0 * 1e-6 / t.kVolume, 1e-9);
  EXPECT_EQ(strips[0].at("kinetic_xx"), 0.0);
  EXPECT_NEAR(strips[1].at("total_yy"), strips[1].at("contact_yy") + strips[1].at("kinetic_yy"), 1e-12);
  EXPECT_TRUE(std::isnan(strips[0].at("collision_rate")));
  // The floor's row: the traction on the particles per area.
  const auto walls = read_rows((t.dir / "walls.csv").string());
  ASSERT_EQ(walls.size(), 1u);
  EXPECT_NEAR(walls[0].at("normal_stress"), t.floor_force.y / t.kArea, 1e-9);
  EXPECT_NEAR(walls[0].at("shear_stress"), t.floor_force.x / t.kArea, 1e-9);
}

}  // namespace
}  // namespace grainflow
