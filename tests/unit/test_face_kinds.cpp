// The face-kind registry (config/face_kinds.hpp): each kind of box face has one line, the parser
// and the writer go through it, and a name it does not hold is refused with the ones it does.
#include <gtest/gtest.h>

#include <set>

#include "grainflow/config/case_writer.hpp"
#include "grainflow/config/face_kinds.hpp"
#include "grainflow/core/error.hpp"
#include "grainflow/run/case_loader.hpp"

namespace grainflow {
namespace {

std::string bed(const std::string& engine, const std::string& y_faces) {
  return R"([engine]
kind = ")" +
         engine + R"("
dimension = 3
[domain]
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.05, 0.02]
boundary = { x = "periodic", y = )" +
         y_faces + R"(, z = "periodic" }
[[species]]
name = "glass"
diameter = 0.003
density = 2490.0
count = 20
[particles]
init = "random"
seed = 3
[run]
duration = 0.01
[output]
interval = 0.001
)" + (engine == "dem" ? "[contact]\nk1 = 1.0e6\nrestitution = 0.9\nfriction = 0.5\n" : "");
}

TEST(FaceKinds, EveryKindHasOneLineWithItsOwnName) {
  std::set<std::string> names;
  for (FaceKind kind : {FaceKind::periodic, FaceKind::wall, FaceKind::bumpy, FaceKind::open}) {
    const FaceKindEntry& e = face_kind_entry(kind);
    EXPECT_EQ(e.kind, kind);
    names.insert(e.name);
    EXPECT_EQ(face_kind_named(e.name), kind);
  }
  EXPECT_EQ(names.size(), std::size(kFaceKinds));
  EXPECT_FALSE(face_kind_named("slippery"));
  EXPECT_EQ(face_kind_names(" or "), "periodic, wall, bumpy or open");
  // A plane wall stands on the wall and bumpy faces only.
  EXPECT_TRUE(holds_wall(FaceKind::wall) && holds_wall(FaceKind::bumpy));
  EXPECT_FALSE(holds_wall(FaceKind::periodic) || holds_wall(FaceKind::open));
}

TEST(FaceKinds, UnknownNameIsRefusedWithTheRegisteredOnes) {
  try {
    load_case_from_string(bed("dem", R"(["slippery", "open"])"), "bed.toml");
    ADD_FAILURE() << "a face named 'slippery' was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "domain.boundary.y");
    EXPECT_NE(e.reason().find("unknown boundary 'slippery' (valid: periodic, wall, bumpy, open)"), std::string::npos)
        << e.reason();
  }
}

TEST(FaceKinds, EventDrivenEngineRefusesSoftSphereOnlyKindsByName) {
  std::string text = bed("edmd", R"(["bumpy", "wall"])");
  text.replace(text.find("[run]"), 5, "[collision]\nrestitution = 0.9\n[run]");
  try {
    load_case_from_string(text, "bed.toml");
    ADD_FAILURE() << "the event-driven engine accepted a bumpy face";
  } catch (const InputError& e) {
    EXPECT_EQ(e.key(), "domain.boundary");
    EXPECT_NE(e.reason().find("bumpy faces (ylo)"), std::string::npos) << e.reason();
    EXPECT_NE(e.reason().find("periodic, wall, open"), std::string::npos) << e.reason();
  }
}

TEST(FaceKinds, WriterSpellsEachFaceAsTheParserReadsIt) {
  const CaseConfig c = load_case_from_string(bed("dem", R"(["wall", "open"])"), "bed.toml");
  const CaseConfig again = load_case_from_string(write_case_toml(c), "written.toml");
  EXPECT_EQ(again.domain.faces, c.domain.faces);
  EXPECT_EQ(again.domain.faces[2], FaceKind::wall);
  EXPECT_EQ(again.domain.faces[3], FaceKind::open);
}

}  // namespace
}  // namespace grainflow
