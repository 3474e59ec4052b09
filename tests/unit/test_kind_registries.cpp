// The registries of the named kinds a case key chooses among: rolling models
// (config/rolling_models.hpp), restitution laws (config/restitution_laws.hpp) and event-driven wall
// conditions (config/wall_conditions.hpp). The engines' own conversions, called with names the
// parser never saw, map every registered name to its kind and refuse any other one with a message
// that lists every registered name: no name falls through to a default.
#include <gtest/gtest.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <tuple>

#include "grainflow/config/restitution_laws.hpp"
#include "grainflow/config/rolling_models.hpp"
#include "grainflow/config/wall_conditions.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/dem/rolling_resistance.hpp"
#include "grainflow/edmd/edmd_state.hpp"
#include "grainflow/run/case_loader.hpp"

namespace grainflow {
namespace {

// What `f` throws as `Error`; a failure, and "", when it throws nothing.
template <class Error>
std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted";
  return "";
}

// `convert` of the name "sticky" throws std::invalid_argument naming the registry (`what`), the
// name, and every name of `table`.
template <class Kind, std::size_t N>
void expect_unknown_name_refused(const KindEntry<Kind> (&table)[N], const std::string& what,
                                 const std::function<void(const std::string&)>& convert) {
  const std::string message = refusal<std::invalid_argument>([&] { convert("sticky"); });
  EXPECT_NE(message.find("unknown " + what + " 'sticky'"), std::string::npos) << message;
  for (const auto& entry : table) EXPECT_NE(message.find(entry.name), std::string::npos) << message;
}

// A small event-driven case with a plane wall at ylo (the state's only wall).
const std::string kEdmdCase = R"([engine]
kind = "edmd"
dimension = 2
[domain]
lo = [0.0, 0.0, 0.0]
hi = [10.0, 10.0, 1.0]
boundary = { x = "periodic", y = ["wall", "open"], z = "periodic" }
[[species]]
name = "disc"
diameter = 0.5
density = 1.0
count = 4
[particles]
init = "lattice"
[run]
duration = 1.0
)";

CaseConfig edmd_case() { return load_case_from_string(kEdmdCase, "registries.toml"); }

TEST(KindRegistries, RollingParamsMapEveryRegisteredModel) {
  ContactConfig contact;
  for (const auto& entry : kRollingModels) {
    contact.rolling_model = entry.name;
    EXPECT_EQ(dem::rolling_params(contact, 0.1, 1e5).model, entry.kind) << entry.name;
  }
  EXPECT_EQ(rolling_model_names(), "none, constant_torque, epsd");
}

TEST(KindRegistries, RollingParamsRefuseAnUnknownModel) {
  expect_unknown_name_refused(kRollingModels, "rolling model", [](const std::string& name) {
    ContactConfig contact;
    contact.rolling_model = name;
    dem::rolling_params(contact, 0.1, 1e5);
  });
}

TEST(KindRegistries, EdmdStateMapsEveryRegisteredRestitutionLaw) {
  CaseConfig c = edmd_case();
  for (const auto& entry : kRestitutionLaws) {
    c.collision.restitution_law = entry.name;
    const edmd::EdmdState s = edmd::build_edmd_state(c);
    EXPECT_EQ(s.restitution.kind, entry.kind) << entry.name;
    ASSERT_EQ(s.walls.size(), 1u);
    EXPECT_EQ(s.walls[0].restitution.kind, entry.kind) << entry.name;
  }
}

TEST(KindRegistries, EdmdStateRefusesAnUnknownRestitutionLaw) {
  expect_unknown_name_refused(kRestitutionLaws, "restitution law", [](const std::string& name) {
    CaseConfig c = edmd_case();
    c.collision.restitution_law = name;
    edmd::build_edmd_state(c);
  });
}

TEST(KindRegistries, EdmdStateMapsEveryRegisteredWallCondition) {
  CaseConfig c = edmd_case();
  for (const auto& entry : kWallConditions) {
    c.walls[2].condition = entry.name;  // ylo
    const edmd::EdmdState s = edmd::build_edmd_state(c);
    ASSERT_EQ(s.walls.size(), 1u);
    EXPECT_EQ(s.walls[0].condition, entry.kind) << entry.name;
  }
}

TEST(KindRegistries, EdmdStateRefusesAnUnknownWallCondition) {
  expect_unknown_name_refused(kWallConditions, "wall condition", [](const std::string& name) {
    CaseConfig c = edmd_case();
    c.walls[2].condition = name;
    edmd::build_edmd_state(c);
  });
}

// The parser refuses the same names through the same tables, naming the key.
TEST(KindRegistries, ParserRefusesAnUnknownNameWithTheRegisteredOnes) {
  for (const auto& [table, key, expected] :
       {std::tuple{"[collision]\nrestitution_law = \"sticky\"\n", "collision.restitution_law",
                   "unknown restitution law 'sticky' (registered: constant, campbell)"},
        std::tuple{"[walls.ylo]\ncondition = \"sticky\"\n", "walls.ylo.condition",
                   "unknown wall condition 'sticky' (registered: smooth, rough, no_slip)"}}) {
    const std::string message =
        refusal<InputError>([&, table = table] { load_case_from_string(kEdmdCase + table, "registries.toml"); });
    EXPECT_NE(message.find(key), std::string::npos) << message;
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace grainflow
