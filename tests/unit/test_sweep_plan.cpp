// `grainflow sweep`'s plan (app/sweep_plan.hpp): --vary specs split into TOML values (commas inside
// brackets, braces and strings do not split), the Cartesian product and --zip, the errors (malformed
// specs, unequal zip lengths, repeated keys and combinations), and folder names that are unique and
// hold only safe characters.
#include <gtest/gtest.h>

#include <cctype>
#include <set>
#include <string>
#include <vector>

#include "grainflow/run/sweep_plan.hpp"
#include "grainflow/core/error.hpp"

using namespace grainflow;
using namespace grainflow::run;

namespace {

const std::string kCase = "cases/test/sweep.toml";

using Strings = std::vector<std::string>;

bool safe(const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name.size() > 200) return false;
  for (const char ch : name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '.' || ch == '_' || ch == '+' || ch == '-' ||
          ch == '=' || ch == '~'))
      return false;
  return true;
}

// The InputError of `call`, or a test failure when it throws none.
template <class F>
InputError input_error(F call) {
  try {
    call();
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError("", "", "");
}

TEST(SweepPlan, SplitsNumbersStringsAndArrays) {
  EXPECT_EQ(split_values("0.5,0.7"), (Strings{"0.5", "0.7"}));
  EXPECT_EQ(split_values(" 1e-3 ,\t2 , -3 "), (Strings{"1e-3", "2", "-3"}));
  EXPECT_EQ(split_values("[1,2],[3,4]"), (Strings{"[1,2]", "[3,4]"}));
  EXPECT_EQ(split_values("[0, 20, 0], [0, 0.5, [1, 2]]"), (Strings{"[0, 20, 0]", "[0, 0.5, [1, 2]]"}));
  EXPECT_EQ(split_values("\"a,b\",'c,d',\"e\\\",f\""), (Strings{"\"a,b\"", "'c,d'", "\"e\\\",f\""}));
  EXPECT_EQ(split_values("{ x = \"periodic\", y = \"wall\" },{x=\"open\"}"),
            (Strings{"{ x = \"periodic\", y = \"wall\" }", "{x=\"open\"}"}));
  EXPECT_EQ(split_values("linear_dashpot"), (Strings{"linear_dashpot"}));
  EXPECT_EQ(split_values("[\"wall\", \"open\"],[\"wall\",\"wall\"]"),
            (Strings{"[\"wall\", \"open\"]", "[\"wall\",\"wall\"]"}));
}

TEST(SweepPlan, SplitRejectsMalformedLists) {
  EXPECT_THROW(split_values(""), std::invalid_argument);
  EXPECT_THROW(split_values("1,,2"), std::invalid_argument);
  EXPECT_THROW(split_values("1,2,"), std::invalid_argument);
  EXPECT_THROW(split_values(" , 1"), std::invalid_argument);
  EXPECT_THROW(split_values("[1,2"), std::invalid_argument);
  EXPECT_THROW(split_values("1,2]"), std::invalid_argument);
  EXPECT_THROW(split_values("[1,2}"), std::invalid_argument);
  EXPECT_THROW(split_values("\"abc,1"), std::invalid_argument);
}

TEST(SweepPlan, ParsesVarySpecs) {
  const SweepVariable a = parse_vary("collision.restitution=0.5,0.7", kCase);
  EXPECT_EQ(a.key, "collision.restitution");
  EXPECT_EQ(a.values, (Strings{"0.5", "0.7"}));
  const SweepVariable b = parse_vary(" species.0.count = 10, 20 ,30", kCase);
  EXPECT_EQ(b.key, "species.0.count");
  EXPECT_EQ(b.values, (Strings{"10", "20", "30"}));
  const SweepVariable c = parse_vary("drive.frequency=[0,20,0],[0,25,0]", kCase);
  EXPECT_EQ(c.values, (Strings{"[0,20,0]", "[0,25,0]"}));
  const SweepVariable d = parse_vary("x.y==1,=2", kCase);  // the first '=' ends the key
  EXPECT_EQ(d.key, "x.y");
  EXPECT_EQ(d.values, (Strings{"=1", "=2"}));
}

TEST(SweepPlan, VarySpecErrorsNameTheKey) {
  InputError e = input_error([] { parse_vary("collision.restitution", kCase); });
  EXPECT_EQ(e.file(), kCase + " (--vary)");
  EXPECT_NE(e.reason().find("KEY=VALUE1,VALUE2"), std::string::npos);
  e = input_error([] { parse_vary("=1,2", kCase); });
  EXPECT_NE(e.reason().find("key is empty"), std::string::npos);
  e = input_error([] { parse_vary("collision.restitution=0.5,,0.7", kCase); });
  EXPECT_EQ(e.key(), "collision.restitution");
  EXPECT_NE(e.reason().find("empty value"), std::string::npos);
  e = input_error([] { parse_vary("drive.amplitude=[0,1,0", kCase); });
  EXPECT_EQ(e.key(), "drive.amplitude");
  e = input_error([] { parse_vary("a b=1", kCase); });
  EXPECT_EQ(e.key(), "a b");
}

TEST(SweepPlan, CartesianProductFirstKeySlowest) {
  const std::vector<SweepVariable> variables = {{"a", {"1", "2"}}, {"b", {"x", "y", "z"}}};
  const auto points = plan_sweep(variables, false, kCase);
  ASSERT_EQ(points.size(), 6u);
  const std::vector<Strings> expected = {{"1", "x"}, {"1", "y"}, {"1", "z"}, {"2", "x"}, {"2", "y"}, {"2", "z"}};
  for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(points[i].values, expected[i]) << i;
  EXPECT_EQ(point_overrides(variables, points[4]), (Strings{"a=2", "b=y"}));
  EXPECT_EQ(describe_point(variables, points[4]), "a=2 b=y");
  // Three variables: 2 x 1 x 2.
  EXPECT_EQ(plan_sweep({{"a", {"1", "2"}}, {"b", {"3"}}, {"c", {"4", "5"}}}, false, kCase).size(), 4u);
}

TEST(SweepPlan, ZipTakesListsElementByElement) {
  const std::vector<SweepVariable> variables = {{"a", {"1", "2", "3"}}, {"b", {"x", "y", "z"}}};
  const auto points = plan_sweep(variables, true, kCase);
  ASSERT_EQ(points.size(), 3u);
  EXPECT_EQ(points[0].values, (Strings{"1", "x"}));
  EXPECT_EQ(points[2].values, (Strings{"3", "z"}));
  // Repeated values in one list are fine as long as the combinations differ.
  EXPECT_EQ(plan_sweep({{"a", {"1", "1"}}, {"b", {"2", "3"}}}, true, kCase).size(), 2u);
}

TEST(SweepPlan, ZipNeedsEqualLengths) {
  const InputError e = input_error([] { plan_sweep({{"a", {"1", "2"}}, {"b", {"1", "2", "3"}}}, true, kCase); });
  EXPECT_EQ(e.key(), "b");
  EXPECT_NE(e.reason().find("equal length"), std::string::npos);
  EXPECT_NE(e.reason().find("'a' has 2"), std::string::npos);
  EXPECT_NE(e.reason().find("'b' has 3"), std::string::npos);
}

TEST(SweepPlan, PlanErrors) {
  EXPECT_NE(input_error([] { plan_sweep({}, false, kCase); }).reason().find("nothing to vary"), std::string::npos);
  EXPECT_EQ(input_error([] { plan_sweep({{"a", {"1"}}, {"a", {"2"}}}, false, kCase); }).key(), "a");
  EXPECT_NE(input_error([] {
              plan_sweep({{"a", {"1", "2", "1"}}}, false, kCase);
            })
                .reason()
                .find("listed twice"),
            std::string::npos);
  EXPECT_NE(input_error([] {
              plan_sweep({{"a", {"1", "1"}}, {"b", {"2", "2"}}}, true, kCase);
            })
                .reason()
                .find("a=1 b=2"),
            std::string::npos);
  // 1000^2 runs is too many.
  SweepVariable big{"a", {}};
  for (int i = 0; i < 1000; ++i) big.values.push_back(std::to_string(i));
  SweepVariable big2 = big;
  big2.key = "b";
  EXPECT_NE(input_error([&] { plan_sweep({big, big2}, false, kCase); }).reason().find("more than"), std::string::npos);
}

TEST(SweepPlan, NamesAreReadable) {
  const auto points = plan_sweep({{"drive.amplitude.1", {"0.001"}}}, false, kCase);
  EXPECT_EQ(points[0].name, "drive.amplitude.1=0.001");
  const std::vector<SweepVariable> two = {{"collision.restitution", {"0.5"}}, {"walls.ylo.restitution", {"-1e-3"}}};
  EXPECT_EQ(plan_sweep(two, false, kCase)[0].name, "collision.restitution=0.5_walls.ylo.restitution=-1e-3");
  EXPECT_EQ(plan_sweep({{"contact.model", {"\"linear_dashpot\""}}}, false, kCase)[0].name,
            "contact.model=linear_dashpot");
  EXPECT_EQ(plan_sweep({{"drive.frequency", {"[0, 20.5, 0]"}}}, false, kCase)[0].name, "drive.frequency=0_20.5_0");
}

TEST(SweepPlan, NamesAreSafeAndUnique) {
  // Values that differ only in characters a folder name cannot hold still get distinct folders.
  const std::vector<SweepVariable> variables = {
      {"species.0.name", {"\"a b\"", "\"a/b\"", "\"a_b\"", "a_b", "\"../..\"", "\"\"", "\"é\"", "\"a\\nb\""}},
      {"run.duration", {"1", "[1,2]"}}};
  const auto points = plan_sweep(variables, false, kCase);
  std::set<std::string> names;
  for (const auto& point : points) {
    EXPECT_TRUE(safe(point.name)) << point.name;
    names.insert(point.name);
  }
  EXPECT_EQ(names.size(), points.size());

  // Very long values are cut, and still unique.
  std::string long_a(400, 'a'), long_b = long_a;
  long_b.back() = 'b';
  const auto cut = plan_sweep({{"k", {"\"" + long_a + "\"", "\"" + long_b + "\""}}}, false, kCase);
  EXPECT_NE(cut[0].name, cut[1].name);
  for (const auto& point : cut) EXPECT_TRUE(safe(point.name)) << point.name;
}

TEST(SweepPlan, SafeNameAndDisplayValue) {
  EXPECT_EQ(safe_name("[\"wall\", \"open\"]"), "wall_open");
  EXPECT_EQ(safe_name("a/../b"), "a_.._b");
  EXPECT_EQ(safe_name("1.5e+3"), "1.5e+3");
  EXPECT_EQ(safe_name("\"\""), "");
  EXPECT_EQ(display_value("\"rough\""), "rough");
  EXPECT_EQ(display_value("'c:\\path'"), "c:\\path");
  EXPECT_EQ(display_value("rough"), "rough");  // a bare word, as --set takes it
  EXPECT_EQ(display_value("1e-3"), "1e-3");    // numbers as written
  EXPECT_EQ(display_value("[0, 1, 0]"), "[0, 1, 0]");
}

}  // namespace
