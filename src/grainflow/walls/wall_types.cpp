#include "grainflow/walls/wall_types.hpp"

#include <array>
#include <algorithm>
#include <stdexcept>
#include <type_traits>

namespace grainflow::walls {
namespace {

template <class... Types>
constexpr std::array<GeometrySchema, sizeof...(Types)> schemas_of(std::variant<Types...>*) {
  return {GeometrySchema{Types::name, Types::meaning, &Types::read}...};
}
constexpr auto kSchemas = schemas_of(static_cast<WallShape*>(nullptr));

template <std::size_t I = 0>
WallShape shape_named(const std::string& type, const GeometryKeys& keys) {
  if constexpr (I < std::variant_size_v<WallShape>) {
    using Type = std::variant_alternative_t<I, WallShape>;
    if (type == Type::name) return Type::from_keys(keys);
    return shape_named<I + 1>(type, keys);
  } else {
    throw std::logic_error("unknown wall type '" + type + "' (registered: " + wall_type_names() + ")");
  }
}

template <std::size_t I = 0>
std::optional<KeyProblem> in_plane_problem_of(const std::string& type, const GeometryKeys& keys, double plane_z) {
  if constexpr (I < std::variant_size_v<WallShape>) {
    using Type = std::variant_alternative_t<I, WallShape>;
    if (type == Type::name) return Type::in_plane_problem(keys, plane_z);
    return in_plane_problem_of<I + 1>(type, keys, plane_z);
  } else {
    throw std::logic_error("unknown wall type '" + type + "' (registered: " + wall_type_names() + ")");
  }
}

}  // namespace

GeometrySchemas geometry_schemas() { return kSchemas; }

std::string wall_type_names() {
  std::string text;
  for (const auto& s : kSchemas) text += (text.empty() ? "" : ", ") + std::string(s.name);
  return text;
}

WallShape make_wall_shape(const GeometryConfig& g) { return shape_named(g.type, g.keys); }

std::optional<KeyProblem> in_plane_problem(const GeometryConfig& g, double plane_z) {
  return in_plane_problem_of(g.type, g.keys, plane_z);
}

double nearest_gap(const WallShape& shape, const Vec3& x, double reach) {
  return std::visit(
      [&](const auto& s) {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, MeshWall>) {
          return s.nearest_distance(x, reach);  // through its tree: a mesh may have 10^5 elements
        } else {
          double gap = s.contact(0, x).gap;
          for (int e = 1; e < s.elements(); ++e) gap = std::min(gap, s.contact(e, x).gap);
          return gap;
        }
      },
      shape);
}

}  // namespace grainflow::walls
