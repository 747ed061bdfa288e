#include "sidecar.h"

#include <fstream>

#include "atomic_file.h"
#include "errors.h"

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
          {"seconds", r.seconds},
          {"intrinsics", intrinsicsToJson(r.rig.camera())},
          {"camera_from_world", matrix}};
}

std::string sidecarPath(const std::string& imagePath) { return imagePath + ".json"; }

void writeSidecarAtomic(const std::string& imagePath, const json& sidecar) {
  writeTextAtomically(sidecarPath(imagePath), sidecar.dump(2) + "\n");
}

RigSpec rigFromSidecar(const std::string& imagePath, RigSpec rig) {
  std::ifstream in(sidecarPath(imagePath));
  if (!in) return rig;
  try {
    const auto j = json::parse(in).at("rig");
    rig.k = j.at("mirror").at("k"), rig.c = j.at("mirror").at("c");
    rig.rimElevationDeg = j.at("mirror").at("rim_elevation_deg");
    rig.framingElevationDeg = j.at("image").at("framing_elevation_deg");
    rig.height = j.at("height");
  } catch (const json::exception& e) {
    throw InputError(sidecarPath(imagePath) + ": rig: " + e.what());
  }
  return rig;
}

}  // namespace omnicam
