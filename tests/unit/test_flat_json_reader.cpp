// The flat JSON reader used by `grainflow sweep` to read each run's summary.json
// (io/flat_json_reader.hpp): scalar fields in order with numbers as written, strings decoded,
// arrays and objects skipped, malformed input refused.
#include <gtest/gtest.h>

#include <limits>
#include <sstream>
#include <string>

#include "grainflow/io/flat_json_reader.hpp"
#include "grainflow/io/json_writer.hpp"

using namespace grainflow::io;

namespace {

TEST(FlatJsonReader, ReadsScalarsInOrderAndSkipsLists) {
  const FlatJsonFields fields = read_flat_json(R"({
  "engine": "edmd",
  "particles": 40,
  "pressure": -1.25e-3,
  "errors": ["a, b", "c]"],
  "nested": {"x": [1, {"y": "}"}], "z": null},
  "ok": true,
  "bad": false,
  "missing": null,
  "empty": [],
  "zero": 0
})");
  ASSERT_EQ(fields.size(), 7u);
  EXPECT_EQ(fields[0].first, "engine");
  EXPECT_EQ(fields[0].second.kind, FlatJsonValue::Kind::string);
  EXPECT_EQ(fields[0].second.text, "edmd");
  EXPECT_EQ(fields[1].first, "particles");
  EXPECT_EQ(fields[1].second.text, "40");
  EXPECT_TRUE(fields[1].second.is_integer());
  EXPECT_EQ(fields[2].second.text, "-1.25e-3");
  EXPECT_EQ(fields[2].second.kind, FlatJsonValue::Kind::number);
  EXPECT_FALSE(fields[2].second.is_integer());
  EXPECT_EQ(fields[3].first, "ok");
  EXPECT_EQ(fields[3].second.kind, FlatJsonValue::Kind::boolean);
  EXPECT_EQ(fields[3].second.text, "true");
  EXPECT_EQ(fields[4].second.text, "false");
  EXPECT_EQ(fields[5].first, "missing");
  EXPECT_EQ(fields[5].second.kind, FlatJsonValue::Kind::null);
  EXPECT_EQ(fields[6].first, "zero");  // after the empty list, which is skipped
  EXPECT_EQ(fields[6].second.text, "0");
}

TEST(FlatJsonReader, DecodesStrings) {
  const FlatJsonFields fields =
      read_flat_json(R"({"a": "q\"b\\s\/n\nt\t", "u": "\u00e9\u20ac\ud83d\ude00", "k\"ey": ""})");
  ASSERT_EQ(fields.size(), 3u);
  EXPECT_EQ(fields[0].second.text, "q\"b\\s/n\nt\t");
  EXPECT_EQ(fields[1].second.text, "\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80");
  EXPECT_EQ(fields[2].first, "k\"ey");
  EXPECT_EQ(fields[2].second.text, "");
}

TEST(FlatJsonReader, RepeatedKeyKeepsFirstPlaceLastValue) {
  const FlatJsonFields fields = read_flat_json(R"({"a": 1, "b": 2, "a": 3})");
  ASSERT_EQ(fields.size(), 2u);
  EXPECT_EQ(fields[0].first, "a");
  EXPECT_EQ(fields[0].second.text, "3");
  EXPECT_TRUE(read_flat_json("{}").empty());
  EXPECT_TRUE(read_flat_json(" \n{ }\n").empty());
}

TEST(FlatJsonReader, RoundTripsTheSummaryWriter) {
  JsonObject summary;
  summary.string("engine", "dem");
  summary.integer("steps", 123456789012LL);
  summary.number("time_step", 1.234567890123e-7);
  summary.number("nan", std::numeric_limits<double>::quiet_NaN());
  summary.boolean("flag", false);
  summary.strings("errors", {"halted, \"overlap\""});
  summary.string("case", "cases/a \"b\".toml");
  std::ostringstream out;
  summary.write(out);
  const FlatJsonFields fields = read_flat_json(out.str());
  ASSERT_EQ(fields.size(), 6u);
  EXPECT_EQ(fields[1].second.text, "123456789012");
  EXPECT_DOUBLE_EQ(std::stod(fields[2].second.text), 1.23456789e-7);
  EXPECT_EQ(fields[3].second.kind, FlatJsonValue::Kind::null);
  EXPECT_EQ(fields[5].first, "case");
  EXPECT_EQ(fields[5].second.text, "cases/a \"b\".toml");
}

TEST(FlatJsonReader, RefusesMalformedInput) {
  for (const char* text : {"", "[]", "{", "{\"a\": }", "{\"a\" 1}", "{a: 1}", "{\"a\": 1,}", "{\"a\": 01}",
                           "{\"a\": 1.}", "{\"a\": .5}", "{\"a\": tru}", "{\"a\": \"x}", "{\"a\": \"\\x\"}",
                           "{\"a\": [1, 2}", "{\"a\": 1} x", "{\"a\": \"tab\there\"}", "{\"a\": -}"})
    EXPECT_THROW(read_flat_json(text), JsonParseError) << text;
  EXPECT_THROW(read_flat_json("{\"a\": " + std::string(2000, '[')), JsonParseError);  // too deep, not a crash
  EXPECT_THROW(read_flat_json_file("/nonexistent/summary.json"), JsonParseError);
}

}  // namespace
