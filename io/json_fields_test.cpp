#include "json_fields.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <functional>
#include <string>

#include "errors.h"
#include "json_text.h"

namespace omnicam {
namespace {

std::string refusal(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

// A missing field beside a near name asks about a typo; beside a sibling of its own (fx, fy) it
// does not, as the sibling may be read later; an unknown field is named with the one meant.
TEST(JsonFields, AMissingFieldAsksAboutATypoButNotAboutASibling) {
  const auto missing = [](const char* text, const char* key) {
    return refusal([&] { JsonFields(nlohmann::json::parse(text), "f.json", "o").number(key); });
  };
  EXPECT_EQ(missing(R"({"line_time": 30})", "line_time_us"),
            "f.json: o.line_time_us: missing required field (the object has line_time: a typo of line_time_us?)");
  EXPECT_EQ(missing(R"({"fx": 30})", "fy"), "f.json: o.fy: missing required field");
  EXPECT_EQ(missing(R"({"edge_v": [1, 0, 0]})", "edge_u"), "f.json: o.edge_u: missing required field");
  EXPECT_EQ(missing(R"({"other": 1})", "fy"), "f.json: o.fy: missing required field");
  // Two letters swapped is a typo, though of the same length one edit away.
  EXPECT_EQ(missing(R"({"materail": "red"})", "material"),
            "f.json: o.material: missing required field (the object has materail: a typo of material?)");
}

// Names a reader asked for with has() are what a typo may mean, as read ones are.
TEST(JsonFields, ATypoOfANameAskedForIsNamedWithIt) {
  const nlohmann::json motion = nlohmann::json::parse(R"({"between_pose": true})");
  EXPECT_EQ(refusal([&] {
              JsonFields fields(motion, "s.json", "motion");
              if (fields.has("velocity") == fields.has("between_poses")) fields.refuseTypos();
            }),
            "s.json: motion.between_pose: unknown field (did you mean between_poses?)");
  EXPECT_EQ(refusal([&] {
              JsonFields fields(nlohmann::json::parse(R"({"timestamp_s": [0, 1]})"), "s.json", "poses");
              fields.has("timestamps_s");
              fields.finish();
            }),
            "s.json: poses.timestamp_s: unknown field (did you mean timestamps_s?)");
}

TEST(JsonDifferences, NameEachDifferingMemberByItsPath) {
  const auto j = [](const char* text) { return nlohmann::json::parse(text); };
  using List = std::vector<std::string>;
  EXPECT_EQ(jsonDifferences(j(R"({"a": 1, "b": {"c": [1, 2, 3]}})"), j(R"({"a": 1, "b": {"c": [1, 2, 3]}})")), List{});
  EXPECT_EQ(jsonDifferences(j(R"({"a": 1, "b": {"c": [1, 2, 3]}})"), j(R"({"a": 2, "b": {"c": [1, 5, 3]}})")), (List{"a", "b.c[1]"}));
  EXPECT_EQ(jsonDifferences(j(R"({"a": 1})"), j(R"({"b": 1})")), (List{"a", "b"}));  // a member either lacks
  EXPECT_EQ(jsonDifferences(j(R"({"a": null})"), j(R"({})")), List{"a"});            // null is not missing
  EXPECT_EQ(jsonDifferences(j(R"({"c": [1, 2]})"), j(R"({"c": [1, 2, 3]})")), List{"c"});  // lengths differ
  EXPECT_EQ(jsonDifferences(j("1"), j("\"1\"")), List{""});
  EXPECT_EQ(jsonDifferences(j("[1, 2, 3, 4, 5]"), j("[0, 0, 0, 0, 0]"), 2), (List{"[0]", "[1]"}));
  // A key is shown as messages show keys: escaped and cut, never a terminal's control sequence or a
  // forged line of output.
  const std::vector<std::string> forged = jsonDifferences(j(R"({"m": {"\u001b[2Jevil\nPASS fake": 1}})"), j(R"({"m": {}})"));
  ASSERT_EQ(forged.size(), 1u);
  EXPECT_EQ(forged[0], "m." + quote("\x1b[2Jevil\nPASS fake"));
  EXPECT_EQ(forged[0].find_first_of("\x1b\n"), std::string::npos) << forged[0];
}

TEST(JsonDifferences, AsMessagesListThem) {
  const auto j = [](const char* text) { return nlohmann::json::parse(text); };
  EXPECT_EQ(jsonDifferenceList(j(R"({"a": 1, "b": 2})"), j(R"({"a": 0, "b": 0})"), "the whole rig"), "a, b");
  EXPECT_EQ(jsonDifferenceList(j("[1, 2, 3]"), j("[0, 0, 0]"), "the whole rig", 2), "[0], [1], and more");
  EXPECT_EQ(jsonDifferenceList(j("1"), j("[1]"), "the whole rig"), "the whole rig");
}

}  // namespace
}  // namespace omnicam
