// The observer registry: a run gets the observers its case asks for, in the registered order, and
// one that builds on another's measurements finds it.
#include <gtest/gtest.h>

#include "grainflow/observe/constitutive_observer.hpp"
#include "grainflow/run/observer_registry.hpp"
#include "observer_fixture.hpp"

namespace grainflow {
namespace {

std::vector<std::string> names(const std::vector<std::unique_ptr<observe::Observer>>& made) {
  std::vector<std::string> out;
  for (const auto& o : made) out.push_back(o->name());
  return out;
}

TEST(ObserverRegistry, SoftSphereRunGetsTheTablesItsCaseEnables) {
  test::ObserverFixture f;
  f.add(1, {0.005, 0.005, 0.005}, {});
  EXPECT_EQ(names(run::make_observers(run::EngineKind::dem, f.context(1e-5), f.at(0.0))),
            (std::vector<std::string>{"profiles"}));  // the zone profiles always
  f.c.tracers.enabled = true;
  ObserverParameters& field = f.c.observer_tables.add("field");  // as [field] with its defaults reads
  field.set_text("axis", "z");
  field.set_number("cell", 0.0);
  field.set_number("interval", 0.0);
  field.set_integer("phase_bins", 8);
  f.c.output.stresses = true;
  f.c.coarse_grain.enabled = true;
  EXPECT_EQ(names(run::make_observers(run::EngineKind::dem, f.context(1e-5), f.at(0.0))),
            (std::vector<std::string>{"field", "tracers", "stresses", "coarse_grain", "profiles"}));
  EXPECT_EQ(run::observer_names(run::EngineKind::dem),
            (std::vector<std::string>{"trajectory", "zone_series", "field", "tracers", "stresses", "coarse_grain",
                                      "geometry", "discharge", "profiles"}));
}

TEST(ObserverRegistry, EventDrivenConstitutiveTableBuildsOnTheProfilesAndStresses) {
  test::ObserverFixture f;
  f.add(1, {0.005, 0.005, 0.005}, {});
  f.add_wall(2, 0.0);
  f.add_wall(3, 0.01);
  f.c.output.collision_stresses = true;
  const auto made = run::make_observers(run::EngineKind::edmd, f.context(0.0), f.at(0.0));
  EXPECT_EQ(names(made), (std::vector<std::string>{"collision_stresses", "profiles", "constitutive"}));
  EXPECT_NE(dynamic_cast<const observe::ConstitutiveObserver*>(made.back().get()), nullptr);
  // Only the collision stresses ask the engine for collisions, and only once averaging began.
  for (const auto& o : made) EXPECT_EQ(o->collision_observer(), nullptr);
}

}  // namespace
}  // namespace grainflow
