// The registered normal-restitution laws of collision.restitution_law (edmd/collision_rules.hpp
// evaluates them). The case parser, the event-driven engine and `theory` convert the name through
// this table.
#pragma once

#include <string>
#include <string_view>

#include "grainflow/config/kind_registry.hpp"

namespace grainflow {

enum class RestitutionLawKind { constant, campbell };

inline constexpr KindEntry<RestitutionLawKind> kRestitutionLaws[] = {
    {RestitutionLawKind::constant, "constant", "e = collision.restitution at every impact speed (the default)"},
    {RestitutionLawKind::campbell, "campbell", "Campbell's e = (1 + exp(-3 dv / velocity_scale)) / 2"},
};

// Throws std::invalid_argument, listing the registered names, for an unknown name.
inline RestitutionLawKind restitution_law_named(std::string_view name) {
  return registered_kind(kRestitutionLaws, name, "restitution law");
}
inline std::string restitution_law_names() { return registered_kind_names(kRestitutionLaws); }

}  // namespace grainflow
