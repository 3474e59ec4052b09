// The registered rolling-resistance models of contact.rolling_model (dem/rolling_resistance.hpp
// has the torques). The case parser and the DEM engine both convert the name through this table.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "grainflow/config/kind_registry.hpp"

namespace grainflow {

enum class RollingModel : std::uint8_t { constant_torque, epsd, none };

inline constexpr KindEntry<RollingModel> kRollingModels[] = {
    {RollingModel::none, "none", "no rolling resistance (the default without rolling_friction)"},
    {RollingModel::constant_torque, "constant_torque", "Ai et al.'s model A: -mu_r R* F_n against the rolling"},
    {RollingModel::epsd, "epsd", "Ai et al.'s model C: a spring-dashpot capped at mu_r R* F_n (the default)"},
};

// Throws std::invalid_argument, listing the registered names, for an unknown name.
inline RollingModel rolling_model_named(std::string_view name) {
  return registered_kind(kRollingModels, name, "rolling model");
}
inline std::string rolling_model_names() { return registered_kind_names(kRollingModels); }

}  // namespace grainflow
