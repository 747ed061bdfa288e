#include "sidecar.h"

#include <cmath>
#include <filesystem>
#include <fstream>

#include "atomic_file.h"
#include "central_camera.h"
#include "errors.h"
#include "file_confinement.h"
#include "lens_fields.h"
#include "make_camera.h"
#include "scene_loader.h"

namespace omnicam {

using nlohmann::json;

namespace {

json shutterToJson(const Shutter& open) {
  json shutter = {{"exposure_s", open.exposureS}};
  if (open.rolling) shutter["rolling"] = {{"line_time_us", open.rolling->lineTimeUs}, {"readout", readoutName(open.rolling->readout)}};
  if (open.timeSamples > 0) shutter["time_samples"] = open.timeSamples;
  return shutter;
}


// rig.mirror, rig.image and (unless ideal) rig.camera.
void addMirrorRig(json& out, const MirrorRig& rig) {
  json mirror = {{"shape", mirrorShapeName(rig.shape)}};
  json image = {{"size", rig.imageSize}};
  std::visit(Overloaded{[&](const HyperboloidMirror& h) {
                          mirror.update({{"k", h.k}, {"c", h.c}, {"rim_elevation_deg", h.rimElevationDeg}});
                          image["framing_elevation_deg"] = h.framingElevationDeg;
                        },
                        [&](const ParaboloidMirror& p) {
                          mirror.update({{"h", p.h}, {"rim_elevation_deg", p.rimElevationDeg}, {"camera_distance_m", p.cameraDistance}});
                        },
                        [&](const SphereMirror& s) {
                          mirror.update({{"radius", s.radius}, {"cap_angle_deg", s.capAngleDeg}, {"camera_distance_m", s.cameraDistance}});
                        },
                        [&](const ConeMirror& c) {
                          mirror.update({{"half_angle_deg", c.halfAngleDeg}, {"rim_radius", c.rimRadius}, {"camera_distance_m", c.cameraDistance}});
                        }},
             rig.shape);
  out["mirror"] = mirror;
  out["image"] = image;
  if (!rig.mount.ideal()) {  // the ideal camera is the default: its rigs read as they always did
    const CameraMount& m = rig.mount;
    const LensDistortion& l = m.distortion;
    out["camera"] = {{"offset_mm", m.offsetMm},
                     {"rotation_deg", m.rotationDeg},
                     {"distortion", {{"k1", l.k1}, {"k2", l.k2}, {"p1", l.p1}, {"p2", l.p2}, {"k3", l.k3}}},
                     {"principal_point_offset_px", m.principalPointOffsetPx}};
  }
}

}  // namespace

json rigToJson(const RigSpec& rig) {
  json out = {{"height", rig.height}};
  std::visit(Overloaded{[&](const MirrorRig& mirror) { addMirrorRig(out, mirror); },
                        [&](const LensCameraSpec& lens) { out["lens"] = lensCameraToJson(lens); }},
             rig.kind);
  if (rig.tiltDeg != std::array<double, 2>{0.0, 0.0}) out["tilt_deg"] = rig.tiltDeg;  // level is the default
  if (!(rig.shutter == Shutter{})) out["shutter"] = shutterToJson(rig.shutter);  // likewise an instant
  return out;
}

json sceneInputsToJson(const std::vector<SceneInputFile>& inputs) {
  json out = json::array();
  for (const SceneInputFile& input : inputs) out.push_back({{"path", input.path}, {"sha256", input.sha256}});
  return out;
}

json poseToJson(const RobotPose& pose) { return {{"x", pose.x}, {"y", pose.y}, {"yaw_deg", pose.yawDeg}}; }

json footPoseToJson(const RobotPose& foot) {
  const double heading = std::remainder(foot.yawDeg, 360.0);  // [−180, 180], −180 where 180 is meant too
  return poseToJson({foot.x, foot.y, heading == -180.0 ? 180.0 : heading});
}

json sidecarJson(const RenderRecord& r) {
  const Rigid cfw = r.placement.worldFromCamera(r.rig).inverse();
  const RobotPose& pose = r.placement.robot();
  const BodyVelocity& velocity = r.placement.velocity();
  json matrix = json::array();
  for (int i = 0; i < 4; ++i) {
    json row = json::array();
    for (int j = 0; j < 4; ++j) row.push_back(cfw.matrix()(i, j));
    matrix.push_back(row);
  }
  json sidecar = {{"engine", r.engine},
          {"engine_version", r.engineVersion},
          {"scene", {{"path", r.scenePath}, {"sha256", r.sceneSha256}, {"inputs", sceneInputsToJson(r.sceneInputs)}}},
          {"pose", poseToJson(pose)},
          {"rig", rigToJson(r.rig)},
          {"spp", r.spp},
          {"shading", r.shading},
          {"mode", r.mode},
          {"mode_options", r.modeOptions},
          {"seconds", r.seconds},
          {"intrinsics", describeCamera(r.rig)},
          {"camera_from_world", matrix}};
  if (!r.pathTracing.is_null()) sidecar["path_tracing"] = r.pathTracing;
  if (!velocity.still())  // the pose and camera_from_world are then the exposure start's
    sidecar["velocity"] = {{"vx", velocity.vx}, {"vy", velocity.vy}, {"yaw_rate_deg_per_s", velocity.yawRateDegPerS}};
  return sidecar;
}

std::string sidecarPath(const std::string& imagePath) { return imagePath + ".json"; }

std::string sidecarText(const json& sidecar) { return sidecar.dump(2) + "\n"; }

void writeSidecarAtomic(const std::string& imagePath, const json& sidecar) {
  writeTextAtomically(sidecarPath(imagePath), sidecarText(sidecar));
}

void checkImageOutput(const std::string& imagePath, const std::string& flag) {
  checkOutputFile(imagePath, flag);
  checkOutputFile(sidecarPath(imagePath), flag + " (its sidecar)");
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
  return sidecar->rig.resized(rig.imageWidth());
}

}  // namespace omnicam
