// render_records: which settings of two renders' records differ, and how a note says it.
#include "render_records.h"

#include <gtest/gtest.h>

namespace omnicam {
namespace {

using nlohmann::json;

json sidecar() {
  return json{{"engine", "fast"},
              {"scene", {{"path", "room.json"}, {"sha256", "919d139ba102d80531b875693ac4b3b2"}, {"inputs", json::array()}}},
              {"pose", {{"x", 0.3}, {"y", -0.2}, {"yaw_deg", 30.0}}},
              {"rig", {{"height", 0.4}, {"mirror", {{"shape", "hyperboloid"}, {"k", 11.546}, {"c", 0.02321}}}}},
              {"spp", 16},
              {"shading", "lit"},
              {"mode", "exact"},
              {"mode_options", json::object()}};
}

TEST(RenderRecords, RecordsOfTheSameRenderSettingsHaveNoNotes) {
  json other = sidecar();
  other["engine"] = "povray";  // another engine is what a comparison is for
  other["seconds"] = 12.5;
  other["scene"]["path"] = "../elsewhere/room.json";  // the same bytes under another name
  EXPECT_TRUE(recordedSettingNotes(sidecar(), other, sidecarSettings()).empty());
}

TEST(RenderRecords, EachDifferingSettingIsOneNote) {
  json other = sidecar();
  other["spp"] = 4;
  other["shading"] = "unlit";
  other["rig"]["mirror"]["k"] = 12.0;
  other["rig"]["height"] = 0.5;
  other["scene"]["sha256"] = "3be1aaaaaaaaaaaaaaaaaaaaaaaaaaaa";
  other["recording"] = {{"exposure_ev", 0.3}};
  EXPECT_EQ(recordedSettingNotes(sidecar(), other, sidecarSettings()),
            (std::vector<std::string>{"scene (its SHA-256) differs: A \"919d139ba102d80531b875693ac4b3b2\", B \"3be1aaaaaaaaaaaaaaaaaaaaaaaaaaaa\"",
                                      "rig differs in height, mirror.k", "shading differs: A \"lit\", B \"unlit\"",
                                      "spp differs: A 16, B 4", "recording camera differs: A none, B has one"}));
}

TEST(RenderRecords, AManifestsSettingsAreReadWhereItHoldsThem) {
  const json a = {{"scene", {{"sha256", "aa"}}}, {"settings", {{"spp", 16}, {"shading", "path"}}}, {"engine", {{"name", "fast"}, {"mode", "exact"}}}};
  json b = a;
  b["engine"]["name"] = "blender";
  EXPECT_TRUE(recordedSettingNotes(a, b, manifestSettings()).empty());
  b["settings"]["spp"] = 36;
  b["spec"] = {{"recording", "webcam"}};
  EXPECT_EQ(recordedSettingNotes(a, b, manifestSettings()),
            (std::vector<std::string>{"spp differs: A 16, B 36", "recording camera differs: A none, B \"webcam\""}));
}

TEST(RenderRecords, PosesAreTheSameToWithinRoundTripping) {
  EXPECT_TRUE(samePose({1.0, 2.0, 30.0}, {1.0 + 1e-12, 2.0, 30.0}));
  EXPECT_FALSE(samePose({1.0, 2.0, 30.0}, {1.0, 2.05, 30.0}));
  EXPECT_FALSE(samePose({1.0, 2.0, 30.0}, {1.0, 2.0, 30.001}));
  // One heading, however written: 0° and 360°, 180° and −180°.
  EXPECT_TRUE(samePose({1.0, 2.0, 0.0}, {1.0, 2.0, 360.0}));
  EXPECT_TRUE(samePose({1.0, 2.0, 180.0}, {1.0, 2.0, -180.0}));
  EXPECT_NEAR(poseDifference({1.0, 2.0, 179.0}, {1.0, 2.0, -179.0}).degrees, 2.0, 1e-12);
  EXPECT_NEAR(poseDifference({0.0, 0.0, 0.0}, {0.03, 0.04, 0.0}).metres, 0.05, 1e-15);  // a 3-4-5 triangle
  EXPECT_EQ(poseText({0.35, -0.2, 30.0}), "(0.35, -0.2, 30°)");
  EXPECT_EQ(poseDifferenceText({0.05, 2.0}), "50 mm and 2° apart");
}

TEST(RenderRecords, ARecordWithoutASettingHoldsWhatItWasBeforeItWasRecorded) {
  json old = sidecar();
  old["scene"].erase("inputs");  // written before scenes' files were recorded: none
  EXPECT_TRUE(recordedSettingNotes(old, sidecar(), sidecarSettings()).empty());
  json withFile = sidecar();
  withFile["scene"]["inputs"] = json::array({{{"path", "wall.png"}, {"sha256", "ab"}}});
  EXPECT_EQ(recordedSettingNotes(old, withFile, sidecarSettings()), std::vector<std::string>{"scene files differs in the whole value"});
}

}  // namespace
}  // namespace omnicam
