// The JSON readers used by `grainflow sweep`, `theory` and `calibrate` to read each run's
// summary.json (io/flat_json_reader.hpp): scalar fields in order with numbers as written, strings
// decoded, arrays and objects skipped, malformed input refused; and the records' writer
// (io/json_writer.hpp): its layout, and nested values that come back through the reader.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <unistd.h>

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

TEST(FlatJsonReader, KeepsEveryNumberLiteralAsWritten) {
  const FlatJsonFields fields =
      read_flat_json(R"({"a": -0, "b": 0, "c": 1E5, "d": -0.0, "e": 99999999999999999999, "f": -12,
                         "g": 18446744073709551615})");
  ASSERT_EQ(fields.size(), 7u);
  for (std::size_t i = 0; i < fields.size(); ++i) EXPECT_EQ(fields[i].second.kind, FlatJsonValue::Kind::number);
  EXPECT_EQ(fields[0].second.text, "-0");
  EXPECT_EQ(fields[1].second.text, "0");
  EXPECT_EQ(fields[2].second.text, "1E5");
  EXPECT_EQ(fields[3].second.text, "-0.0");
  EXPECT_EQ(fields[4].second.text, "99999999999999999999");
  EXPECT_EQ(fields[5].second.text, "-12");
  EXPECT_EQ(fields[6].second.text, "18446744073709551615");
}

TEST(FlatJsonReader, NamesTheFileAndWhereItBreaks) {
  const std::filesystem::path path =
      std::filesystem::path(testing::TempDir()) / ("grainflow_bad_summary_" + std::to_string(::getpid()) + ".json");
  std::ofstream(path) << "{\n  \"a\": 1,\n  \"b\": }\n";
  try {
    read_flat_json_file(path.string());
    ADD_FAILURE() << "malformed file accepted";
  } catch (const JsonParseError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(path.string() + ": invalid JSON at line 3, column 8"), std::string::npos) << what;
    EXPECT_NE(what.find("unexpected '}'"), std::string::npos) << what;
  }
  std::filesystem::remove(path);
  for (const char* top : {"[1, 2]", "3", "\"text\""}) {
    try {
      read_flat_json(top);
      ADD_FAILURE() << top << " accepted";
    } catch (const JsonParseError& e) {
      EXPECT_NE(std::string(e.what()).find("not an object"), std::string::npos) << e.what();
    }
  }
}

TEST(JsonObject, WritesOneFieldALineWithNumbersInTenDigits) {
  JsonObject record;
  record.number("third", 1.0 / 3.0);
  record.number("whole", 3.0);
  record.number("large", 1.5e12);
  record.number("small", -2.5e-5);
  record.number("negative_zero", -0.0);
  record.number("infinite", std::numeric_limits<double>::infinity());
  record.integer("steps", -7);
  record.strings("empty", {});
  record.string("text", "a\tb\x01");
  record.number("third", 0.5);  // again: first place, last value
  std::ostringstream out;
  record.write(out);
  EXPECT_EQ(out.str(), R"({
  "third": 0.5,
  "whole": 3,
  "large": 1.5e+12,
  "small": -2.5e-05,
  "negative_zero": -0,
  "infinite": null,
  "steps": -7,
  "empty": [],
  "text": "a\tb\u0001"
}
)");
  std::ostringstream empty;
  JsonObject().write(empty);
  EXPECT_EQ(empty.str(), "{\n}\n");
}

TEST(JsonObject, NestedValuesRoundTripThroughWriterAndReader) {
  // An array and an object inside summary-like output, as observers with nested results write them.
  const nlohmann::ordered_json strips = {0.25, -1.5e-7, 12, nullptr};
  const nlohmann::ordered_json wall = {
      {"face", "ylo"}, {"stress", {1.25, -3.5}}, {"steady", true}, {"counts", {{"n", 4}}}};
  JsonObject summary;
  summary.string("engine", "edmd");
  summary.value("strip_centres", strips);
  summary.value("wall", wall);
  summary.integer("steps", 12);
  std::ostringstream out;
  summary.write(out);
  EXPECT_EQ(out.str(), R"({
  "engine": "edmd",
  "strip_centres": [0.25, -1.5e-07, 12, null],
  "wall": {"face": "ylo", "stress": [1.25, -3.5], "steady": true, "counts": {"n": 4}},
  "steps": 12
}
)");
  const nlohmann::ordered_json back = read_json(out.str());
  EXPECT_EQ(back, summary.fields());
  EXPECT_EQ(back.at("strip_centres"), strips);
  EXPECT_EQ(back.at("wall"), wall);
  EXPECT_EQ(back.at("wall").begin().key(), "face");  // the order written
  // The flat reader still sees the scalars around them.
  const FlatJsonFields fields = read_flat_json(out.str());
  ASSERT_EQ(fields.size(), 2u);
  EXPECT_EQ(fields[0].first, "engine");
  EXPECT_EQ(fields[1].first, "steps");
  EXPECT_EQ(fields[1].second.text, "12");
}

}  // namespace
