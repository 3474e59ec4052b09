#include "grainflow/run/observer_registry.hpp"

#include <stdexcept>

#include "grainflow/observe/coarse_grain_observer.hpp"
#include "grainflow/observe/collision_stress_observer.hpp"
#include "grainflow/observe/constitutive_observer.hpp"
#include "grainflow/observe/contact_stress_observer.hpp"
#include "grainflow/observe/convection_observer.hpp"
#include "grainflow/observe/discharge_observer.hpp"
#include "grainflow/observe/geometry_observer.hpp"
#include "grainflow/observe/state_trajectory_observer.hpp"
#include "grainflow/observe/strip_profile_observer.hpp"
#include "grainflow/observe/tracer_observer.hpp"
#include "grainflow/observe/window_trajectory_observer.hpp"
#include "grainflow/observe/zone_profile_observer.hpp"
#include "grainflow/observe/zone_series_observer.hpp"

namespace grainflow::run {
namespace {

using Made = std::unique_ptr<observe::Observer>;

struct Registered {
  const char* name;
  EngineKind engine;
  // An observer that owns its case table hands over its schema (its table present asks for it);
  // one whose table config/ still reads says when the case asks for it.
  const ObserverSchema* table;
  bool (*wanted)(const CaseConfig&);
  // `before`: the observers made so far, for one that builds on another's measurements.
  Made (*make)(const observe::RunContext&, const observe::Frame& start, const std::vector<Made>& before);
};

template <class T>
const T& find(const std::vector<Made>& made) {
  for (const auto& m : made)
    if (const auto* t = dynamic_cast<const T*>(m.get())) return *t;
  throw std::logic_error("an observer is registered before the one it builds on");
}

// The `wanted` of an observer that owns its table: the table's presence asks for it.
constexpr bool (*kByTable)(const CaseConfig&) = nullptr;

// One line per observer.
constexpr Registered kObservers[] = {
    {"trajectory", EngineKind::dem, nullptr, [](const CaseConfig& c) { return c.trajectory.enabled; },
     [](const observe::RunContext& run, const observe::Frame& start, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::WindowTrajectoryObserver>(run, *start.particles);
     }},
    {"zone_series", EngineKind::dem, &observe::ZoneSeriesObserver::table, kByTable,
     [](const observe::RunContext& run, const observe::Frame&, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::ZoneSeriesObserver>(run);
     }},
    {"field", EngineKind::dem, &observe::ConvectionObserver::table, kByTable,
     [](const observe::RunContext& run, const observe::Frame&, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::ConvectionObserver>(run);
     }},
    {"tracers", EngineKind::dem, nullptr, [](const CaseConfig& c) { return c.tracers.enabled; },
     [](const observe::RunContext& run, const observe::Frame& start, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::TracerObserver>(run, *start.particles);
     }},
    {"stresses", EngineKind::dem, nullptr, [](const CaseConfig& c) { return c.output.stresses; },
     [](const observe::RunContext& run, const observe::Frame& start, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::ContactStressObserver>(run, start);
     }},
    {"coarse_grain", EngineKind::dem, nullptr, [](const CaseConfig& c) { return c.coarse_grain.enabled; },
     [](const observe::RunContext& run, const observe::Frame& start, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::CoarseGrainObserver>(run, start);
     }},
    {"geometry", EngineKind::dem, nullptr, [](const CaseConfig& c) { return !c.geometry.empty(); },
     [](const observe::RunContext& run, const observe::Frame&, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::GeometryObserver>(run);
     }},
    {"discharge", EngineKind::dem, nullptr, [](const CaseConfig& c) { return !c.outlets.empty(); },
     [](const observe::RunContext& run, const observe::Frame&, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::DischargeObserver>(run);
     }},
    {"profiles", EngineKind::dem, nullptr, [](const CaseConfig&) { return true; },
     [](const observe::RunContext& run, const observe::Frame&, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::ZoneProfileObserver>(run);
     }},
    // Event-driven: the collision stresses write before the strip profiles (their warnings first).
    {"collision_stresses", EngineKind::edmd, nullptr, [](const CaseConfig& c) { return c.output.collision_stresses; },
     [](const observe::RunContext& run, const observe::Frame& start, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::CollisionStressObserver>(run, start);
     }},
    {"profiles", EngineKind::edmd, nullptr, [](const CaseConfig&) { return true; },
     [](const observe::RunContext& run, const observe::Frame& start, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::StripProfileObserver>(run, start);
     }},
    {"trajectory", EngineKind::edmd, nullptr, [](const CaseConfig& c) { return c.trajectory.enabled; },
     [](const observe::RunContext& run, const observe::Frame& start, const std::vector<Made>&) -> Made {
       return std::make_unique<observe::StateTrajectoryObserver>(run, start);
     }},
    {"constitutive", EngineKind::edmd, nullptr, [](const CaseConfig& c) { return c.output.collision_stresses; },
     [](const observe::RunContext& run, const observe::Frame&, const std::vector<Made>& before) -> Made {
       return std::make_unique<observe::ConstitutiveObserver>(run, find<observe::StripProfileObserver>(before),
                                                              find<observe::CollisionStressObserver>(before));
     }},
};

bool wanted(const Registered& r, const CaseConfig& c) {
  return r.table ? c.observer_tables.has(r.table->table) : r.wanted(c);
}

}  // namespace

std::vector<Made> make_observers(EngineKind engine, const observe::RunContext& run, const observe::Frame& start) {
  std::vector<Made> made;
  for (const Registered& r : kObservers)
    if (r.engine == engine && wanted(r, *run.c)) made.push_back(r.make(run, start, made));
  return made;
}

ObserverSchemas observer_schemas() {
  static const std::vector<ObserverSchema> schemas = [] {
    std::vector<ObserverSchema> list;
    for (const Registered& r : kObservers)
      if (r.table) list.push_back(*r.table);
    return list;
  }();
  return schemas;
}

std::vector<std::string> observer_names(EngineKind engine) {
  std::vector<std::string> names;
  for (const Registered& r : kObservers)
    if (r.engine == engine) names.emplace_back(r.name);
  return names;
}

}  // namespace grainflow::run
