#pragma once
// The JSON sidecar written next to every image (docs/conventions.md §5): provenance and the intrinsics and
// extrinsics needed to use the image with OpenCV's cv::omnidir.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "placement.h"
#include "rig.h"
#include "scene.h"

namespace omnicam {

struct RenderRecord {
  std::string engine, engineVersion;
  std::string scenePath, sceneSha256;
  std::vector<SceneInputFile> sceneInputs;  // the files the scene reads beyond its own text
  CameraPlacement placement;  // the robot's pose at the exposure start, its velocity (docs/motion.md)
  RigSpec rig;
  int spp = 1;
  std::string shading, mode = "exact";
  nlohmann::json modeOptions = nlohmann::json::object();  // e.g. {"faces": 6, "face_size": 512}
  nlohmann::json pathTracing;  // path-traced frames: pathTracingRecord (request/path_tracing_record.h); null otherwise
  double seconds = 0.0;
};

nlohmann::json rigToJson(const RigSpec& rig);
// A robot's pose as records write it: {"x", "y", "yaw_deg"}, as given.
nlohmann::json poseToJson(const RobotPose& pose);
// A camera's foot pose (CameraPlacement::footAt) as records write it: its heading, the robot's
// plus its mount's, within (−180°, 180°] (a robot at 180° with a camera mounted backwards heads
// 0°, not 360°; one heading one number); renders keep the sum as it is.
nlohmann::json footPoseToJson(const RobotPose& foot);
// [{"path", "sha256"}, ...]: the scene's files beyond its own text (Scene::inputDigests).
nlohmann::json sceneInputsToJson(const std::vector<SceneInputFile>& inputs);
nlohmann::json sidecarJson(const RenderRecord& record);
// Sidecar path of an image: OUT + ".json".
std::string sidecarPath(const std::string& imagePath);
void writeSidecarAtomic(const std::string& imagePath, const nlohmann::json& sidecar);
// The bytes of a sidecar file, as writeSidecarAtomic writes them.
std::string sidecarText(const nlohmann::json& sidecar);
// checkOutputFile for an image and the sidecar written beside it: both names are checked before
// the image is written, so a refused sidecar never leaves its image behind.
void checkImageOutput(const std::string& imagePath, const std::string& flag);
// A sidecar's text, read strictly: valid JSON, no duplicate keys, an object with a "rig" that
// passes the same checks as a scene's rig. InputError naming `path` otherwise.
struct SidecarInfo {
  nlohmann::json json;
  RigSpec rig;
};
SidecarInfo sidecarFromText(const std::string& text, const std::string& path);
// The sidecar of an image, if it has one.
std::optional<SidecarInfo> readSidecar(const std::string& imagePath);
// The rig an image was rendered with, from its sidecar: mirror and framing replace `fallback`'s;
// `fallback` unchanged if there is no sidecar. Throws InputError for an unreadable one.
RigSpec rigFromSidecar(const std::string& imagePath, RigSpec fallback);

}  // namespace omnicam
