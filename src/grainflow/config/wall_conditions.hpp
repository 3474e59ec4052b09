// The registered conditions of an event-driven wall, walls.<face>.condition (edmd/collision_rules.hpp
// applies them). The case parser, the event-driven engine and `theory` convert the name through
// this table.
#pragma once

#include <string>
#include <string_view>

#include "grainflow/config/kind_registry.hpp"

namespace grainflow {

enum class WallCondition { rough, no_slip, smooth };

inline constexpr KindEntry<WallCondition> kWallConditions[] = {
    {WallCondition::smooth, "smooth", "only the normal velocity changes (the default)"},
    {WallCondition::rough, "rough", "the contact point leaves with the wall's velocity, spin changes too"},
    {WallCondition::no_slip, "no_slip", "the particle leaves with the wall's tangential velocity, spin kept"},
};

// Throws std::invalid_argument, listing the registered names, for an unknown name.
inline WallCondition wall_condition_named(std::string_view name) {
  return registered_kind(kWallConditions, name, "wall condition");
}
inline std::string wall_condition_names() { return registered_kind_names(kWallConditions); }

}  // namespace grainflow
