// What both run drivers share (run/run_support.hpp): final_state.csv.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "grainflow/run/run_support.hpp"

namespace grainflow::run {
namespace {

// The rows of a CSV file after its units and header lines: the first field of each (the id).
std::vector<std::string> first_fields(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> ids;
  std::string line;
  std::getline(in, line);  // units
  std::getline(in, line);  // header
  while (std::getline(in, line)) ids.push_back(line.substr(0, line.find(',')));
  return ids;
}

// A silo's outlet takes particles out and an insertion adds new ids: the ids of a final state are
// then neither 0 .. N - 1 nor in order. Each particle is written once, in id order, with its own
// position.
TEST(FinalState, WritesEveryParticleOnceInIdOrderWhateverItsIds) {
  ParticleStore p;
  p.resize(4);
  const std::uint32_t ids[] = {70, 3, 41, 12};  // N = 4, ids up to 70
  for (std::size_t i = 0; i < 4; ++i) {
    p.id[i] = ids[i];
    p.species[i] = 0;
    p.target_radius[i] = 0.5;
    p.position[i] = Vec3{static_cast<double>(ids[i]), 0.0, 0.0};
  }
  std::vector<SpeciesConfig> species(1);
  species[0].name = "grain";
  const std::string path = (std::filesystem::temp_directory_path() / "grainflow_final_state_ids.csv").string();
  write_final_state(path, p, species);
  EXPECT_EQ(first_fields(path), (std::vector<std::string>{"3", "12", "41", "70"}));
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::getline(in, line);
  while (std::getline(in, line)) {  // x is the id: each row's position is its own particle's
    std::stringstream row(line);
    std::string id, name, diameter, x;
    std::getline(row, id, ',');
    std::getline(row, name, ',');
    std::getline(row, diameter, ',');
    std::getline(row, x, ',');
    EXPECT_EQ(std::stod(x), std::stod(id));
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace grainflow::run
