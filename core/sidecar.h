#pragma once
// The JSON sidecar written next to every image (spec §7): provenance and the intrinsics and
// extrinsics needed to use the image with OpenCV's cv::omnidir.
#include <nlohmann/json.hpp>
#include <string>

#include "rig.h"

namespace omnicam {

struct RenderRecord {
  std::string engine, engineVersion;
  std::string scenePath, sceneSha256;
  RobotPose pose;
  RigSpec rig;
  int spp = 1;
  std::string shading, mode = "exact";
  double seconds = 0.0;
};

nlohmann::json rigToJson(const RigSpec& rig);
nlohmann::json intrinsicsToJson(const OmniCamera& camera);
nlohmann::json sidecarJson(const RenderRecord& record);
// Sidecar path of an image: OUT + ".json".
std::string sidecarPath(const std::string& imagePath);
void writeSidecarAtomic(const std::string& imagePath, const nlohmann::json& sidecar);
// The rig an image was rendered with, from its sidecar: mirror and framing replace `fallback`'s;
// `fallback` unchanged if there is no sidecar. Throws InputError for an unreadable one.
RigSpec rigFromSidecar(const std::string& imagePath, RigSpec fallback);

}  // namespace omnicam
