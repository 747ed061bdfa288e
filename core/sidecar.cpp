#include "sidecar.h"

#include <filesystem>
#include <fstream>

#include "atomic_file.h"
#include "errors.h"
#include "file_confinement.h"
#include "scene_loader.h"

namespace omnicam {

using nlohmann::json;

json rigToJson(const RigSpec& rig) {
  return {{"height", rig.height},
          {"mirror", {{"k", rig.k}, {"c", rig.c}, {"rim_elevation_deg", rig.rimElevationDeg}}},
          {"image", {{"size", rig.imageSize}, {"framing_elevation_deg", rig.framingElevationDeg}}}};
}

json intrinsicsToJson(const OmniCamera& camera) {
  const OpenCvIntrinsics k = camera.openCvIntrinsics();
  return {{"model", "mei_unified"},
          {"xi", k.xi},
          {"gamma_x", k.gamma_x},
          {"gamma_y", k.gamma_y},
          {"cx", k.cx},
          {"cy", k.cy},
          {"pixel_centre", "integer"},
          {"distortion", {0.0, 0.0, 0.0, 0.0}},
          {"width", camera.width()},
          {"height", camera.height()},
          {"rim_radius_px", camera.rimRadius()},
          {"horizon_radius_px", camera.horizonRadius()},
          {"note",
           "camera frame at the effective viewpoint: X forward, Y right (-robot y), Z down; "
           "gamma_y < 0 because the catadioptric image is a mirror image of a top-down map"}};
}

json sidecarJson(const RenderRecord& r) {
  const Rigid cfw = cameraFromWorld(r.rig, r.pose);
  json matrix = json::array();
  for (int i = 0; i < 4; ++i) {
    json row = json::array();
    for (int j = 0; j < 4; ++j) row.push_back(cfw.matrix()(i, j));
    matrix.push_back(row);
  }
  return {{"engine", r.engine},
          {"engine_version", r.engineVersion},
          {"scene", {{"path", r.scenePath}, {"sha256", r.sceneSha256}}},
          {"pose", {{"x", r.pose.x}, {"y", r.pose.y}, {"yaw_deg", r.pose.yawDeg}}},
          {"rig", rigToJson(r.rig)},
          {"spp", r.spp},
          {"shading", r.shading},
          {"mode", r.mode},
          {"mode_options", r.modeOptions},
          {"seconds", r.seconds},
          {"intrinsics", intrinsicsToJson(r.rig.camera())},
          {"camera_from_world", matrix}};
}

std::string sidecarPath(const std::string& imagePath) { return imagePath + ".json"; }

void writeSidecarAtomic(const std::string& imagePath, const json& sidecar) {
  writeTextAtomically(sidecarPath(imagePath), sidecar.dump(2) + "\n");
}

SidecarInfo sidecarFromText(const std::string& text, const std::string& path) {
  SidecarInfo info;
  info.json = parseJsonText(text, path);
  if (!info.json.is_object()) throw InputError(showPath(path) + ": a sidecar must be a JSON object");
  const auto rig = info.json.find("rig");
  if (rig == info.json.end()) throw InputError(showPath(path) + ": rig: missing required field");
  info.rig = rigFromJson(*rig, path, "rig");
  return info;
}

std::optional<SidecarInfo> readSidecar(const std::string& imagePath) {
  const std::string path = sidecarPath(imagePath);
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return std::nullopt;
  std::string why;
  const auto text = readWholeFile(path, why, limits::kMaxJsonFileBytes);
  if (!text) throw InputError(showPath(path) + ": cannot read sidecar (" + why + ")");
  return sidecarFromText(*text, path);
}

RigSpec rigFromSidecar(const std::string& imagePath, RigSpec rig) {
  const auto sidecar = readSidecar(imagePath);
  if (!sidecar) return rig;
  const int size = rig.imageSize;
  rig = sidecar->rig;
  rig.imageSize = size;
  return rig;
}

}  // namespace omnicam
