// The registered kinds of box face, the boundary conditions and wall types a case's
// domain.boundary names: one line each with its name, what it does, and which engines take it. The
// case parser and writer, the checks and the messages read this table; nothing else spells a name.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "grainflow/config/case_config.hpp"

namespace grainflow {

struct FaceKindEntry {
  FaceKind kind;
  const char* name;
  const char* meaning;  // for messages and `grainflow check`
  bool holds_wall;      // particles meet a plane wall there (FaceWall)
  bool event_driven;    // the event-driven engine takes it too
};

inline constexpr FaceKindEntry kFaceKinds[] = {
    {FaceKind::periodic, "periodic", "the opposite face's images (both faces of the axis)", false, true},
    {FaceKind::wall, "wall", "a flat plane wall (section 2.6.2), moving when driven", true, true},
    {FaceKind::bumpy, "bumpy", "a flat wall carrying a lattice of fixed spheres (section 2.6.3)", true, false},
    {FaceKind::open, "open", "nothing: particles leave the box there", false, true},
};

inline const FaceKindEntry& face_kind_entry(FaceKind kind) {
  for (const auto& e : kFaceKinds)
    if (e.kind == kind) return e;
  return kFaceKinds[0];  // unreachable: every enumerator has its line
}
inline const char* face_kind_name(FaceKind kind) { return face_kind_entry(kind).name; }
inline std::optional<FaceKind> face_kind_named(std::string_view name) {
  for (const auto& e : kFaceKinds)
    if (name == e.name) return e.kind;
  return std::nullopt;
}
// "periodic, wall, bumpy, open", or with `last` before the last name ("periodic, wall, bumpy or open").
inline std::string face_kind_names(std::string_view last = ", ") {
  std::string out;
  const std::size_t n = std::size(kFaceKinds);
  for (std::size_t i = 0; i < n; ++i) out += std::string(i == 0 ? "" : i + 1 == n ? last : ", ") + kFaceKinds[i].name;
  return out;
}
inline bool holds_wall(FaceKind kind) { return face_kind_entry(kind).holds_wall; }

}  // namespace grainflow
