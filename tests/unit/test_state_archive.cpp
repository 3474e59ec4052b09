// The checkpoint archive (io/state_archive.hpp): one serialize() writes and reads back every kind
// of member bit for bit, and a reader that drifts out of step fails loudly instead of restoring a
// wrong state.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "grainflow/core/vec3.hpp"
#include "grainflow/io/state_archive.hpp"

namespace grainflow::io {
namespace {

struct Inner {
  std::vector<double> values;
  std::string name;
  template <class Archive>
  void serialize(Archive& ar) {
    ar(values, name);
  }
};

struct Outer {
  double x = 0.0;
  long steps = 0;
  Vec3 v;
  std::vector<Vec3> positions;
  std::vector<std::vector<std::uint8_t>> nested;
  std::array<int, 3> cells{};
  std::optional<Inner> maybe;
  std::vector<Inner> inners;
  template <class Archive>
  void serialize(Archive& ar) {
    ar.tag("outer");
    ar(x, steps, v, positions, nested, cells, maybe, inners);
  }
};

Outer example() {
  Outer o;
  o.x = std::nextafter(0.1, 1.0);  // a value whose last bit matters
  o.steps = 123456789012L;
  o.v = {-0.0, std::numeric_limits<double>::denorm_min(), 1e300};
  o.positions = {{1, 2, 3}, {4, 5, 6}};
  o.nested = {{1, 2}, {}, {3}};
  o.cells = {7, 8, 9};
  o.maybe = Inner{{0.5, 0.25}, "inner"};
  o.inners = {Inner{{1.0}, "a"}, Inner{{}, ""}};
  return o;
}

TEST(StateArchive, RoundTripIsBitwise) {
  Outer original = example();
  StateArchive out = StateArchive::for_writing();
  out(original);
  Outer restored;
  StateArchive in = StateArchive::for_reading(out.bytes(), "test.h5");
  in(restored);
  in.expect_end();
  EXPECT_EQ(std::memcmp(&restored.x, &original.x, sizeof(double)), 0);
  EXPECT_EQ(restored.steps, original.steps);
  EXPECT_TRUE(std::signbit(restored.v.x));  // -0.0 kept as such
  EXPECT_EQ(restored.v.y, original.v.y);
  EXPECT_EQ(restored.positions.size(), 2u);
  EXPECT_EQ(restored.positions[1].z, 6.0);
  EXPECT_EQ(restored.nested, original.nested);
  EXPECT_EQ(restored.cells, original.cells);
  ASSERT_TRUE(restored.maybe.has_value());
  EXPECT_EQ(restored.maybe->name, "inner");
  EXPECT_EQ(restored.maybe->values, original.maybe->values);
  ASSERT_EQ(restored.inners.size(), 2u);
  EXPECT_EQ(restored.inners[0].name, "a");

  // Writing the restored object gives the same bytes: nothing was lost or reordered.
  StateArchive again = StateArchive::for_writing();
  again(restored);
  EXPECT_EQ(again.bytes(), out.bytes());
}

TEST(StateArchive, AnAbsentOptionalIsRestoredAbsent) {
  Outer original = example();
  original.maybe.reset();
  StateArchive out = StateArchive::for_writing();
  out(original);
  Outer restored = example();  // holds a value that must go
  StateArchive in = StateArchive::for_reading(out.bytes(), "test.h5");
  in(restored);
  EXPECT_FALSE(restored.maybe.has_value());
}

TEST(StateArchive, TruncatedStateFailsWithTheFileName) {
  Outer original = example();
  StateArchive out = StateArchive::for_writing();
  out(original);
  std::vector<std::uint8_t> cut(out.bytes().begin(), out.bytes().begin() + out.bytes().size() / 2);
  Outer restored;
  StateArchive in = StateArchive::for_reading(cut, "half.h5");
  try {
    in(restored);
    FAIL() << "a truncated state was read";
  } catch (const RunError& e) {
    EXPECT_NE(std::string(e.what()).find("half.h5"), std::string::npos) << e.what();
  }
}

TEST(StateArchive, ExtraBytesAndWrongTagsAreRefused) {
  Outer original = example();
  StateArchive out = StateArchive::for_writing();
  out(original);
  double extra = 1.0;
  out(extra);
  Outer restored;
  StateArchive in = StateArchive::for_reading(out.bytes(), "long.h5");
  in(restored);
  EXPECT_THROW(in.expect_end(), RunError);

  StateArchive other = StateArchive::for_writing();
  other.tag("something else");
  StateArchive wrong = StateArchive::for_reading(other.bytes(), "other.h5");
  EXPECT_THROW(wrong(restored), RunError);
}

TEST(StateArchive, ADamagedLengthIsRefusedBeforeAllocating) {
  std::vector<std::uint8_t> bytes(8, 0xff);  // a vector length of 2^64 - 1 elements
  std::vector<double> v;
  StateArchive in = StateArchive::for_reading(bytes, "damaged.h5");
  EXPECT_THROW(in(v), RunError);
}

}  // namespace
}  // namespace grainflow::io
