#include "dataset_spec.h"

#include <cmath>
#include <filesystem>
#include <set>

#include "errors.h"
#include "file_confinement.h"
#include "input_limits.h"
#include "json_fields.h"
#include "scene_loader.h"
#include "sha256.h"

namespace omnicam {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

constexpr const char* kFormat = "omnicam-dataset/1";
// More frames than anyone renders in one folder; keeps indices in six digits.
constexpr int kMaxFrames = 999999;
constexpr int kMaxCameras = 16;

}  // namespace

bool isCameraFolderName(const std::string& name) {
  if (name.empty() || name.size() > 63 || name == "intrinsics") return false;
  for (char ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') return false;
  return true;
}

namespace {

RobotPose readPose(const json& value, const std::string& file, const std::string& where) {
  const Vec3 p = jsonVec3(value, file, where);
  RobotPose pose{p.x(), p.y(), p.z()};
  checkPose(pose, showPath(file) + ": " + where);
  return pose;
}

void readPoses(JsonFields poses, DatasetSpec& spec) {
  const int sources = poses.has("path") + poses.has("list") + poses.has("random");
  if (sources != 1)
    throw InputError(showPath(spec.file) + ": poses: give exactly one of \"path\", \"list\" or \"random\"");
  if (poses.has("path")) {
    spec.poseSource = PoseSource::Path;
    spec.pathName = poses.string("path");
    spec.pathFrames = poses.integer("frames", 0, 1, kMaxFrames);
  } else if (poses.has("list")) {
    spec.poseSource = PoseSource::List;
    const json& list = poses.raw("list");
    if (!list.is_array() || list.empty() || list.size() > static_cast<size_t>(kMaxFrames))
      poses.fail("list", "must be a non-empty array of [x, y, yaw_deg]");
    for (size_t i = 0; i < list.size(); ++i)
      spec.poseList.push_back(readPose(list[i], spec.file, poses.path("list[" + std::to_string(i) + "]")));
  } else {
    spec.poseSource = PoseSource::Random;
    JsonFields r = poses.object("random");
    RandomPoses& rp = spec.random;
    rp.count = r.integer("count", 0, 1, kMaxFrames);
    if (!r.has("count")) r.fail("count", "missing required field");
    const double seed = r.number("seed");
    if (!(seed >= 0 && seed <= 9007199254740992.0) || std::floor(seed) != seed)
      r.fail("seed", "must be an integer in [0, 2^53]");
    rp.seed = static_cast<uint64_t>(seed);
    const json& region = r.raw("region");
    if (!region.is_array() || region.size() != 4)
      r.fail("region", "must be [x_min, y_min, x_max, y_max] in metres");
    double v[4];
    for (int i = 0; i < 4; ++i) {
      if (!region[i].is_number()) r.fail("region", "must be [x_min, y_min, x_max, y_max] in metres");
      v[i] = region[i].get<double>();
      if (!(std::abs(v[i]) <= limits::kMaxWorldCoordinate)) r.fail("region", "coordinates must lie within ±10 km");
    }
    if (!(v[0] < v[2] && v[1] < v[3])) r.fail("region", "needs x_min < x_max and y_min < y_max");
    rp.xMin = v[0], rp.yMin = v[1], rp.xMax = v[2], rp.yMax = v[3];
    rp.clearance = r.nonNegative("clearance", 0.0);
    if (r.has("yaw_deg")) {
      const json& yaw = r.raw("yaw_deg");
      if (!yaw.is_array() || yaw.size() != 2 || !yaw[0].is_number() || !yaw[1].is_number())
        r.fail("yaw_deg", "must be [min, max] in degrees");
      rp.yawMinDeg = yaw[0].get<double>(), rp.yawMaxDeg = yaw[1].get<double>();
      if (!(rp.yawMinDeg <= rp.yawMaxDeg) || std::abs(rp.yawMinDeg) > limits::kMaxYawDeg ||
          std::abs(rp.yawMaxDeg) > limits::kMaxYawDeg)
        r.fail("yaw_deg", "must be [min, max] with min <= max, both within ±" + std::to_string(static_cast<int>(limits::kMaxYawDeg)));
    }
    r.finish();
  }
  poses.finish();
}

// The rule a camera name broke; the name itself too when it holds characters the user cannot
// see in it (control characters, bytes that are not UTF-8), shown escaped.
std::string cameraNameProblem(const std::string& name) {
  const std::string rule = "must be 1 to 63 letters, digits, '_' or '-' (a folder name; not \"intrinsics\"";
  return rule + (oneLine(name) != name ? "; got " + quote(name) : "") + ")";
}

void readCameras(const json& cameras, DatasetSpec& spec) {
  if (!cameras.is_array() || cameras.empty() || cameras.size() > kMaxCameras)
    throw InputError(showPath(spec.file) + ": cameras: must be an array of 1 to " + std::to_string(kMaxCameras) + " cameras");
  std::set<std::string> names;
  for (size_t i = 0; i < cameras.size(); ++i) {
    JsonFields c(cameras[i], spec.file, "cameras[" + std::to_string(i) + "]");
    DatasetCamera camera;
    camera.name = c.string("name");
    if (!isCameraFolderName(camera.name)) c.fail("name", cameraNameProblem(camera.name));
    if (!names.insert(camera.name).second) c.fail("name", "duplicate camera name " + quote(camera.name));
    if (c.has("rig")) {
      camera.rig = c.raw("rig");
      rigFromJson(*camera.rig, spec.file, c.path("rig"));  // validated now, applied with the scene
    }
    if (auto mount = c.optionalObject("mount")) {
      camera.mountX = mount->number("x", 0.0);
      camera.mountY = mount->number("y", 0.0);
      camera.mountYawDeg = mount->number("yaw_deg", 0.0);
      if (std::abs(camera.mountX) > 100.0 || std::abs(camera.mountY) > 100.0)
        mount->fail("x", "mount offsets must lie within ±100 m of the robot");
      if (std::abs(camera.mountYawDeg) > 360.0) mount->fail("yaw_deg", "must lie within ±360");
      mount->finish();
    }
    c.finish();
    spec.cameras.push_back(std::move(camera));
  }
}

void readOutputs(JsonFields o, DatasetSpec& spec) {
  DatasetOutputs& out = spec.outputs;
  out.rgb = o.string("rgb", out.rgb);
  if (out.rgb != "png" && out.rgb != "exr") o.fail("rgb", "must be \"png\" or \"exr\"");
  out.depth = o.boolean("depth", out.depth);
  out.instance = o.boolean("instance", out.instance);
  out.semantic = o.boolean("semantic", out.semantic);
  out.normal = o.boolean("normal", out.normal);
  out.landmarks = o.boolean("landmarks", out.landmarks);
  o.finish();
}

}  // namespace

DatasetSpec loadDatasetSpec(const std::string& file) {
  std::string why;
  const auto text = readWholeFile(file, why, limits::kMaxJsonFileBytes);
  if (!text) throw InputError(showPath(file) + ": cannot open dataset spec (" + why + ")");
  return datasetSpecFromText(*text, file);
}

DatasetSpec datasetSpecFromText(const std::string& text, const std::string& file) {
  DatasetSpec spec;
  spec.file = file;
  spec.sha256 = sha256OfBytes(text);
  spec.json = parseJsonText(text, file);
  JsonFields top(spec.json, file, "");
  if (top.string("format") != kFormat) top.fail("format", "must be \"" + std::string(kFormat) + "\"");
  top.string("description", "");
  if (top.has("comment")) top.raw("comment");
  const std::string scene = top.string("scene");
  if (scene.empty()) top.fail("scene", "must name a scene file");
  const fs::path scenePath(scene);
  spec.scene = scenePath.is_absolute() ? scene : (fs::path(file).parent_path() / scenePath).lexically_normal().string();
  if (spec.scene.empty()) spec.scene = scene;
  spec.allowOutsideFiles = top.boolean("allow_outside_files", false);
  spec.engine = top.string("engine", spec.engine);
  if (spec.engine != "fast" && spec.engine != "povray" && spec.engine != "blender")
    top.fail("engine", "must be fast, povray or blender (got " + quote(spec.engine) + ")");
  spec.mode = top.string("mode", spec.mode);
  if (spec.mode != "exact" && spec.mode != "cubemap" && spec.mode != "thesis-mesh")
    top.fail("mode", "must be exact, cubemap or thesis-mesh (got " + quote(spec.mode) + ")");
  if (spec.mode != "exact" && spec.engine != "fast") top.fail("mode", "only the fast engine has modes other than exact");
  if (auto options = top.optionalObject("mode_options")) {
    if (spec.mode == "exact") top.fail("mode_options", "only with mode cubemap or thesis-mesh");
    spec.faces = options->integer("faces", spec.faces, 5, 6);
    spec.faceSize = options->integer("face_size", spec.faceSize, 8, 8192);
    if (options->has("polygons")) {
      if (spec.mode != "thesis-mesh") options->fail("polygons", "only with mode thesis-mesh");
      spec.polygons = options->integer("polygons", spec.polygons, 16, 1024);
    }
    options->finish();
  }
  spec.spp = top.integer("spp", spec.spp, 1, limits::kMaxSpp);
  if (!samplesPerAxis(spec.spp)) top.fail("spp", "must be a perfect square (1, 4, 9, 16, ...)");
  const auto shading = parseShading(top.string("shading", "unlit"));
  if (!shading) top.fail("shading", "must be unlit or lit");
  spec.shading = *shading;
  if (top.has("size")) spec.size = top.integer("size", 360, 8, limits::kMaxImageSize);
  if (top.has("timeout_s")) {
    if (spec.engine == "fast") top.fail("timeout_s", "only for the povray and blender engines");
    spec.timeoutSeconds = top.positive("timeout_s");
  }
  spec.frameIntervalSeconds = top.positive("frame_interval_s", spec.frameIntervalSeconds);
  readPoses(top.object("poses"), spec);
  if (top.has("cameras")) {
    readCameras(top.raw("cameras"), spec);
  } else {
    spec.cameras.push_back({"cam0", std::nullopt, 0.0, 0.0, 0.0});
  }
  if (auto outputs = top.optionalObject("outputs")) readOutputs(*outputs, spec);
  if (top.has("recording")) spec.recording = recordingCameraFromJson(top.raw("recording"), showPath(file) + ": recording");
  top.finish();
  return spec;
}

RobotPose cameraPose(const DatasetCamera& camera, const RobotPose& robot) {
  const double yaw = radians(robot.yawDeg);
  return {robot.x + std::cos(yaw) * camera.mountX - std::sin(yaw) * camera.mountY,
          robot.y + std::sin(yaw) * camera.mountX + std::cos(yaw) * camera.mountY,
          robot.yawDeg + camera.mountYawDeg};
}

}  // namespace omnicam
