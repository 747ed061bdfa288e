#include "render_records.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "errors.h"
#include "json_text.h"
#include "json_fields.h"
#include "sidecar.h"

namespace omnicam {

namespace {

constexpr double kPoseTolerance = 1e-9;

// A scalar as a note shows it: numbers and booleans as written, strings quoted (escaped).
std::string scalarText(const nlohmann::json& value) {
  if (value.is_null()) return "none";
  if (value.is_string()) return quote(value.get<std::string>(), 64);  // a SHA-256 whole
  return value.dump();
}

// How two values of a setting differ: scalars by their values, objects and arrays by their differing
// members, one missing by which record has it.
std::string differenceText(const nlohmann::json& a, const nlohmann::json& b) {
  if (!a.is_structured() && !b.is_structured()) return ": A " + scalarText(a) + ", B " + scalarText(b);
  if (a.is_null() || b.is_null()) return std::string(": A ") + (a.is_null() ? "none" : "has one") + ", B " + (b.is_null() ? "none" : "has one");
  return " in " + jsonDifferenceList(a, b, "the whole value");
}

}  // namespace

PoseDifference poseDifference(const RobotPose& a, const RobotPose& b) {
  return {std::hypot(a.x - b.x, a.y - b.y), std::abs(std::remainder(a.yawDeg - b.yawDeg, 360.0))};  // 0° and 360° one heading
}

bool samePose(const RobotPose& a, const RobotPose& b) {
  const PoseDifference d = poseDifference(a, b);
  return d.metres <= kPoseTolerance && d.degrees <= kPoseTolerance;
}

std::string poseText(const RobotPose& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g°)", p.x, p.y, p.yawDeg);
  return text;
}

std::string poseDifferenceText(const PoseDifference& d) {
  char text[96];
  std::snprintf(text, sizeof text, "%.3g mm and %.3g° apart", d.metres * 1000.0, d.degrees);
  return text;
}

const std::vector<RecordedSetting>& sidecarSettings() {
  static const std::vector<RecordedSetting> settings = {
      {"scene (its SHA-256)", "/scene/sha256"}, {"scene files", "/scene/inputs", nlohmann::json::array()}, {"rig", "/rig"},
      {"velocity", "/velocity"}, {"shading", "/shading"}, {"spp", "/spp"}, {"mode", "/mode"},
      {"mode options", "/mode_options"}, {"path tracing", "/path_tracing"}, {"recording camera", "/recording"}, {"view", "/view"}};
  return settings;
}

const std::vector<RecordedSetting>& manifestSettings() {
  static const std::vector<RecordedSetting> settings = {
      {"scene (its SHA-256)", "/scene/sha256"}, {"scene files", "/scene/inputs", nlohmann::json::array()},
      {"shading", "/settings/shading"}, {"spp", "/settings/spp"}, {"mode", "/engine/mode"},
      {"mode options", "/engine/mode_options"}, {"frame interval", "/settings/frame_interval_s"},
      {"recording camera", "/spec/recording"}};
  return settings;
}

std::vector<std::string> recordedSettingNotes(const nlohmann::json& a, const nlohmann::json& b,
                                              const std::vector<RecordedSetting>& settings) {
  std::vector<std::string> notes;
  for (const RecordedSetting& setting : settings) {
    const nlohmann::json::json_pointer pointer(setting.pointer);
    // A record written before the setting was recorded holds its value when absent (no scene files: []).
    const auto at = [&](const nlohmann::json& record) {
      return record.is_object() && record.contains(pointer) ? record.at(pointer) : setting.absent;
    };
    const nlohmann::json valueA = at(a), valueB = at(b);
    if (valueA != valueB) notes.push_back(std::string(setting.name) + " differs" + differenceText(valueA, valueB));
  }
  return notes;
}

SidecarComparison compareSidecars(const std::string& imageA, const std::string& imageB) {
  std::optional<SidecarInfo> a, b;
  std::optional<RobotPose> poseA, poseB;
  SidecarComparison out;
  try {
    a = readSidecar(imageA);
    b = readSidecar(imageB);
    if (!a || !b) return out;
    const auto poseOf = [](const SidecarInfo& sidecar, const std::string& image) -> std::optional<RobotPose> {
      if (!sidecar.json.contains("pose")) return std::nullopt;
      JsonFields pose(sidecar.json["pose"], sidecarPath(image), "pose");
      return RobotPose{pose.number("x"), pose.number("y"), pose.number("yaw_deg")};
    };
    poseA = poseOf(*a, imageA);
    poseB = poseOf(*b, imageB);
  } catch (const InputError& e) {
    out.notes.push_back(std::string(e.what()) + ": the images' records are not compared");
    return out;
  }
  if (poseA && poseB && !samePose(*poseA, *poseB)) {
    const PoseDifference d = poseDifference(*poseA, *poseB);
    out.poses = "A " + poseText(*poseA) + ", B " + poseText(*poseB) + " (" + poseDifferenceText(d) + ")";
    out.posesApart = d.metres > kSamePoseToTheEyeMetres || d.degrees > kSamePoseToTheEyeDegrees;
  }
  out.notes = recordedSettingNotes(a->json, b->json, sidecarSettings());
  return out;
}

}  // namespace omnicam
