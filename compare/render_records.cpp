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
  constexpr size_t kShown = 4;
  const std::vector<std::string> paths = jsonDifferences(a, b, kShown + 1);
  std::string list;
  for (size_t k = 0; k < std::min(paths.size(), kShown); ++k) list += (k ? ", " : "") + (paths[k].empty() ? "the whole value" : paths[k]);
  if (paths.size() > kShown) list += ", and more";
  return " in " + list;
}

}  // namespace

bool samePose(const RobotPose& a, const RobotPose& b) {
  return std::abs(a.x - b.x) <= kPoseTolerance && std::abs(a.y - b.y) <= kPoseTolerance &&
         std::abs(a.yawDeg - b.yawDeg) <= kPoseTolerance;
}

std::string poseText(const RobotPose& p) {
  char text[96];
  std::snprintf(text, sizeof text, "(%.6g, %.6g, %.6g°)", p.x, p.y, p.yawDeg);
  return text;
}

const std::vector<RecordedSetting>& sidecarSettings() {
  static const std::vector<RecordedSetting> settings = {
      {"scene (its SHA-256)", "/scene/sha256"}, {"the scene's files", "/scene/inputs"}, {"rig", "/rig"},
      {"velocity", "/velocity"}, {"shading", "/shading"}, {"spp", "/spp"}, {"mode", "/mode"},
      {"mode options", "/mode_options"}, {"path tracing", "/path_tracing"}, {"recording camera", "/recording"}};
  return settings;
}

const std::vector<RecordedSetting>& manifestSettings() {
  static const std::vector<RecordedSetting> settings = {
      {"scene (its SHA-256)", "/scene/sha256"}, {"the scene's files", "/scene/inputs"}, {"shading", "/settings/shading"},
      {"spp", "/settings/spp"}, {"mode", "/engine/mode"}, {"mode options", "/engine/mode_options"},
      {"frame interval", "/settings/frame_interval_s"}, {"recording camera", "/spec/recording"}};
  return settings;
}

std::vector<std::string> recordedSettingNotes(const nlohmann::json& a, const nlohmann::json& b,
                                              const std::vector<RecordedSetting>& settings) {
  std::vector<std::string> notes;
  const auto at = [](const nlohmann::json& record, const nlohmann::json::json_pointer& pointer) {
    return record.is_object() && record.contains(pointer) ? record.at(pointer) : nlohmann::json();
  };
  for (const RecordedSetting& setting : settings) {
    const nlohmann::json::json_pointer pointer(setting.pointer);
    const nlohmann::json valueA = at(a, pointer), valueB = at(b, pointer);
    if (valueA != valueB) notes.push_back(std::string(setting.name) + " differs" + differenceText(valueA, valueB));
  }
  return notes;
}

std::vector<std::string> sidecarNotes(const std::string& imageA, const std::string& imageB) {
  std::optional<SidecarInfo> a, b;
  std::optional<RobotPose> poseA, poseB;
  try {
    a = readSidecar(imageA);
    b = readSidecar(imageB);
    if (!a || !b) return {};
    const auto poseOf = [](const SidecarInfo& sidecar, const std::string& image) -> std::optional<RobotPose> {
      if (!sidecar.json.contains("pose")) return std::nullopt;
      JsonFields pose(sidecar.json["pose"], sidecarPath(image), "pose");
      return RobotPose{pose.number("x"), pose.number("y"), pose.number("yaw_deg")};
    };
    poseA = poseOf(*a, imageA);
    poseB = poseOf(*b, imageB);
  } catch (const InputError& e) {
    return {std::string(e.what()) + ": the images' records are not compared"};
  }
  if (poseA && poseB && !samePose(*poseA, *poseB))
    throw InputError(showPath(imageB) + ": rendered at pose " + poseText(*poseB) + ", " + showPath(imageA) + " at " +
                     poseText(*poseA) + " (their sidecars): images of different poses are not compared");
  return recordedSettingNotes(a->json, b->json, sidecarSettings());
}

}  // namespace omnicam
