#include "dataset_spec.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include "data_files.h"
#include "errors.h"
#include "file_confinement.h"
#include "input_limits.h"
#include "json_fields.h"
#include "number_format.h"
#include "scene_loader.h"
#include "sha256.h"

namespace omnicam {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {


}  // namespace

// Names the dataset folder keeps for itself: a camera's folder beside them would mix with them.
constexpr std::array<const char*, 3> kReservedFolderNames = {"intrinsics", "shards", "slurm"};

bool isReservedFolderName(const std::string& name) {
  return std::find(kReservedFolderNames.begin(), kReservedFolderNames.end(), name) != kReservedFolderNames.end();
}

bool isCameraFolderName(const std::string& name) {
  if (name.empty() || name.size() > 63 || name == "intrinsics") return false;
  for (char ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-') return false;
  return true;
}

void checkFrameCount(const DatasetSpec& spec, size_t frames, const std::string& field) {
  const std::string where = showPath(spec.file) + ": " + field + ": ";
  if (frames > static_cast<size_t>(limits::kMaxDatasetFrames))
    throw InputError(where + std::to_string(frames) + " frames; the limit is " + std::to_string(limits::kMaxDatasetFrames));
  const size_t cameraFrames = frames * spec.cameras.size();
  if (cameraFrames > static_cast<size_t>(limits::kMaxCameraFrames))
    throw InputError(where + std::to_string(frames) + " frames x " + std::to_string(spec.cameras.size()) + " cameras = " +
                     std::to_string(cameraFrames) + " camera-frames; the limit is " + std::to_string(limits::kMaxCameraFrames) +
                     " (each is an entry of the manifest, which is read whole)");
}

SettingNames settingNames(const DatasetSpec& spec) { return {showPath(spec.file) + ": spp", showPath(spec.file) + ": size"}; }

namespace {

// [x_min, y_min, x_max, y_max] within the world's bounds, not empty.
void readRegion(JsonFields& r, RandomPoses& rp) {
  const json& region = r.raw("region");
  const std::string rule = "must be [x_min, y_min, x_max, y_max] in metres";
  if (!region.is_array() || region.size() != 4) r.fail("region", rule);
  double v[4];
  for (int i = 0; i < 4; ++i) {
    if (!region[i].is_number()) r.fail("region", rule);
    v[i] = region[i].get<double>();
    if (!(std::abs(v[i]) <= limits::kMaxWorldCoordinate))
      r.fail("region", "coordinates must lie within ±" + shortNumber(limits::kMaxWorldCoordinate) + " m (got " + roundTrip(v[i]) + ")");
  }
  if (!(v[0] < v[2] && v[1] < v[3])) r.fail("region", "needs x_min < x_max and y_min < y_max");
  rp.xMin = v[0], rp.yMin = v[1], rp.xMax = v[2], rp.yMax = v[3];
}

void readRandomPoses(JsonFields r, RandomPoses& rp) {
  rp.count = static_cast<int>(r.integer("count", 1, limits::kMaxDatasetFrames));
  rp.seed = static_cast<uint64_t>(r.integer("seed", 0, limits::kMaxSeed));
  readRegion(r, rp);
  rp.clearance = r.number("clearance", 0.0, {0.0, limits::kMaxClearance, false, "m"});
  if (r.has("yaw_deg")) {
    const json& yaw = r.raw("yaw_deg");
    if (!yaw.is_array() || yaw.size() != 2 || !yaw[0].is_number() || !yaw[1].is_number())
      r.fail("yaw_deg", "must be [min, max] in degrees");
    rp.yawMinDeg = yaw[0].get<double>(), rp.yawMaxDeg = yaw[1].get<double>();
    if (!(rp.yawMinDeg <= rp.yawMaxDeg) || std::abs(rp.yawMinDeg) > limits::kMaxYawDeg ||
        std::abs(rp.yawMaxDeg) > limits::kMaxYawDeg)
      r.fail("yaw_deg", "must be [min, max] with min <= max, both within ±" + shortNumber(limits::kMaxYawDeg));
  }
  r.finish();
}

// A path's or list's poses as waypoints driven in time (trajectory.h): "speed_m_s" with
// "yaw_rate_deg_per_s", or "timestamps_s" (one per waypoint, strictly increasing).
void readTiming(JsonFields& poses, DatasetSpec& spec) {
  const bool speed = poses.has("speed_m_s") || poses.has("yaw_rate_deg_per_s"), stamps = poses.has("timestamps_s");
  if (!speed && !stamps) return;
  if (spec.poseSource == PoseSource::Random)
    poses.fail(stamps ? "timestamps_s" : "speed_m_s", "times a path or a list of waypoints, not random poses");
  if (speed && stamps) poses.fail("timestamps_s", "give either timestamps_s or speed_m_s with yaw_rate_deg_per_s, not both");
  PathTiming& timing = spec.timing;
  if (speed) {
    timing.kind = PathTiming::Kind::Speed;
    timing.speed = poses.number("speed_m_s", {0.0, limits::kMaxSpeed, true, "m/s"});
    timing.yawRateDegPerS = poses.number("yaw_rate_deg_per_s", {0.0, limits::kMaxYawRateDegPerS, true, "degrees/s"});
    return;
  }
  timing.kind = PathTiming::Kind::Timestamps;
  const json& list = poses.raw("timestamps_s");
  if (!list.is_array() || list.empty()) poses.fail("timestamps_s", "must be a non-empty array of seconds, one per waypoint");
  for (size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_number() || !std::isfinite(list[i].get<double>()) || std::abs(list[i].get<double>()) > limits::kMaxTimestampSeconds)
      poses.fail("timestamps_s", "[" + std::to_string(i) + "] must be a number of seconds within ±" + shortNumber(limits::kMaxTimestampSeconds));
    const double t = list[i].get<double>();
    if (!timing.timestamps.empty() && !(t > timing.timestamps.back()))
      poses.fail("timestamps_s", "[" + std::to_string(i) + "] must be later than the one before it");
    timing.timestamps.push_back(t);
  }
  if (spec.poseSource == PoseSource::List && timing.timestamps.size() != spec.poseList.size())
    poses.fail("timestamps_s", "has " + std::to_string(timing.timestamps.size()) + " timestamps for " +
                                   std::to_string(spec.poseList.size()) + " waypoints");
}

void readPoses(JsonFields poses, DatasetSpec& spec) {
  const int sources = poses.has("path") + poses.has("list") + poses.has("random");
  if (sources != 1) {
    poses.refuseTypos();
    throw InputError(showPath(spec.file) + ": poses: give exactly one of \"path\", \"list\" or \"random\"");
  }
  if (poses.has("path")) {
    spec.poseSource = PoseSource::Path;
    spec.pathName = poses.string("path");
    spec.pathFrames = poses.integer("frames", 0, 1, limits::kMaxDatasetFrames);
    if (spec.pathFrames) checkFrameCount(spec, static_cast<size_t>(spec.pathFrames), poses.path("frames"));
  } else if (poses.has("list")) {
    spec.poseSource = PoseSource::List;
    const json& list = poses.raw("list");
    if (!list.is_array() || list.empty()) poses.fail("list", "must be a non-empty array of [x, y, yaw_deg]");
    checkFrameCount(spec, list.size(), poses.path("list"));
    for (size_t i = 0; i < list.size(); ++i)
      spec.poseList.push_back(poseFromJson(list[i], spec.file, poses.path("list[" + std::to_string(i) + "]")));
  } else {
    spec.poseSource = PoseSource::Random;
    readRandomPoses(poses.object("random"), spec.random);
    checkFrameCount(spec, static_cast<size_t>(spec.random.count), poses.path("random.count"));
  }
  readTiming(poses, spec);
  if (spec.timing.kind != PathTiming::Kind::None) {
    // Frames every frame_interval_s along the timed waypoints; "frames" caps how many.
    spec.pathFrames = poses.integer("frames", 0, 1, limits::kMaxDatasetFrames);
  }
  poses.finish();
}

// A listed board's origin from the viewpoint F' (m), as a drawn board's centre (distance_m).
using limits::kMinBoardDistanceM, limits::kMaxBoardDistanceM;

// A listed board pose: {"origin": [x, y, z], "x_axis": [...], "y_axis": [...]} in the first
// camera's viewpoint frame (docs/conventions.md), as a scene places a target.
Rigid readListedBoardPose(JsonFields p) {
  const Vec3 origin = p.vec3("origin"), xAxis = p.vec3("x_axis"), yAxis = p.vec3("y_axis");
  if (!(xAxis.norm() > 1e-9)) p.fail("x_axis", "must not be zero");
  if (!(yAxis.norm() > 1e-9)) p.fail("y_axis", "must not be zero");
  const Vec3 x = xAxis.normalized();
  if (std::abs(x.dot(yAxis.normalized())) > 1e-6) p.fail("y_axis", "must be perpendicular to x_axis");
  if (!(origin.norm() >= kMinBoardDistanceM && origin.norm() <= kMaxBoardDistanceM))
    p.fail("origin", "must be " + shortNumber(kMinBoardDistanceM) + " to " + shortNumber(kMaxBoardDistanceM) +
                         " m from the viewpoint (the camera sits at it)");
  p.finish();
  const Vec3 z = x.cross(yAxis).normalized();
  Rigid pose = Rigid::Identity();
  pose.linear().col(0) = x;
  pose.linear().col(1) = z.cross(x);
  pose.linear().col(2) = z;
  pose.translation() = origin;
  return pose;
}

// "calibration": {"target": NAME, "poses": {"random": {...}} or {"list": [...]}, "rosbag": bool}.
void readCalibration(JsonFields c, DatasetSpec& spec) {
  CalibrationSequenceSpec cal;
  cal.target = c.string("target");
  JsonFields poses = c.object("poses");
  if (poses.has("random") == poses.has("list")) {
    poses.refuseTypos();
    throw InputError(showPath(spec.file) + ": calibration.poses: give exactly one of \"random\" or \"list\"");
  }
  if (poses.has("random")) {
    JsonFields r = poses.object("random");
    BoardPoseOptions o;
    o.count = static_cast<int>(r.integer("count", 1, limits::kMaxCalibrationPoses));
    o.seed = static_cast<uint64_t>(r.integer("seed", 0, limits::kMaxSeed));
    const std::vector<double> distance = r.numbers("distance_m", {o.nearM, o.farM}, {kMinBoardDistanceM, kMaxBoardDistanceM, false, "m"});
    if (!(distance[0] < distance[1])) r.fail("distance_m", "must be [near, far] with near < far");
    o.nearM = distance[0], o.farM = distance[1];
    o.maxTiltDeg = r.number("max_tilt_deg", o.maxTiltDeg, {0.0, 80.0, false, "degrees"});
    o.minSeenCorners = r.integer("min_seen_corners", o.minSeenCorners, 4, 1000000);
    r.finish();
    cal.random = o;
  } else {
    const json& list = poses.raw("list");
    if (!list.is_array() || list.empty() || list.size() > static_cast<size_t>(limits::kMaxCalibrationPoses))
      poses.fail("list", "must be an array of 1 to " + std::to_string(limits::kMaxCalibrationPoses) +
                             " board poses {\"origin\", \"x_axis\", \"y_axis\"}");
    for (size_t i = 0; i < list.size(); ++i) {
      if (!list[i].is_object()) poses.fail("list[" + std::to_string(i) + "]", "must be an object {\"origin\", \"x_axis\", \"y_axis\"}");
      cal.listed.push_back(readListedBoardPose(JsonFields(list[i], spec.file, poses.path("list[" + std::to_string(i) + "]"))));
    }
  }
  poses.finish();
  cal.rosbag = c.boolean("rosbag", false);
  c.finish();
  const size_t frames = cal.random ? static_cast<size_t>(cal.random->count) : cal.listed.size();
  checkFrameCount(spec, frames, c.path("poses"));
  // The robot stands still while the board moves: its one pose, every frame.
  if (spec.poseSource != PoseSource::List || spec.poseList.size() != 1 || spec.timing.kind != PathTiming::Kind::None)
    throw InputError(showPath(spec.file) + ": calibration: the robot stands still while the board moves: give poses as {\"list\": [[x, y, yaw_deg]]}, one pose");
  if (spec.motion != MotionSource::Still || !spec.vibration.none())
    throw InputError(showPath(spec.file) + ": calibration: the exact corners are a still camera's: leave motion and vibration out");
  if (cal.rosbag && (spec.layout != DatasetLayout::Files || spec.outputs.rgb != "png"))
    throw InputError(showPath(spec.file) + ": calibration.rosbag: needs the files layout and outputs.rgb \"png\" (the bag holds the PNG frames' pixels)");
  if (cal.rosbag && !(spec.frameIntervalSeconds * 1e9 >= 1.0))
    throw InputError(showPath(spec.file) + ": calibration.rosbag: needs frame_interval_s of at least 1 ns (each image's stamp is its frame's time in ns)");
  spec.calibration = std::move(cal);
}

// "motion": {"velocity": [vx, vy, yaw_rate_deg_per_s]} or {"between_poses": true}.
void readMotion(JsonFields motion, DatasetSpec& spec) {
  if (motion.has("velocity") == motion.has("between_poses")) {
    motion.refuseTypos();
    throw InputError(showPath(spec.file) + ": motion: give exactly one of \"velocity\" or \"between_poses\"");
  }
  if (motion.has("velocity")) {
    const std::vector<double> v = motion.numbers("velocity", {0.0, 0.0, 0.0},
                                                 {-limits::kMaxYawRateDegPerS, limits::kMaxYawRateDegPerS, false, ""});
    spec.motion = MotionSource::Constant;
    spec.velocity = {v[0], v[1], v[2]};
    if (!(std::hypot(v[0], v[1]) <= limits::kMaxSpeed))
      motion.fail("velocity", "speed must be at most " + shortNumber(limits::kMaxSpeed) + " m/s");
  } else {
    if (!motion.boolean("between_poses", false)) motion.fail("between_poses", "must be true (or leave motion out)");
    if (spec.poseSource == PoseSource::Random)
      motion.fail("between_poses", "needs poses in an order (a path or a list), not random ones");
    spec.motion = MotionSource::BetweenPoses;
  }
  motion.finish();
}

// "vibration": {"seed": N, "camera_offset_mm": [x, y, z], "camera_rotation_deg": [x, y, z],
// "rig_tilt_deg": [roll, pitch]}: amplitudes, each absent one 0.
void readVibration(JsonFields fields, DatasetSpec& spec) {
  Vibration& v = spec.vibration;
  v.seed = static_cast<uint64_t>(fields.integer("seed", 0, limits::kMaxSeed));
  const auto amplitudes = [&](const char* key, size_t count, double maximum, const char* unit) {
    return fields.numbers(key, std::vector<double>(count, 0.0), {0.0, maximum, false, unit});
  };
  const std::vector<double> offset = amplitudes("camera_offset_mm", 3, limits::kMaxVibrationOffsetMm, "mm");
  const std::vector<double> rotation = amplitudes("camera_rotation_deg", 3, limits::kMaxVibrationRotationDeg, "degrees");
  const std::vector<double> tilt = amplitudes("rig_tilt_deg", 2, limits::kMaxVibrationTiltDeg, "degrees");
  const std::vector<double> robotTilt = amplitudes("robot_tilt_deg", 2, limits::kMaxVibrationTiltDeg, "degrees");
  v.cameraOffsetMm = {offset[0], offset[1], offset[2]};
  v.cameraRotationDeg = {rotation[0], rotation[1], rotation[2]};
  v.rigTiltDeg = {tilt[0], tilt[1]};
  v.robotTiltDeg = {robotTilt[0], robotTilt[1]};
  fields.finish();  // a misspelt amplitude is named before "no amplitude" could blame the spec
  if (v.none()) throw InputError(showPath(spec.file) + ": vibration: needs an amplitude above 0 (or leave vibration out)");
}

// The rule a camera name broke, and the name, quoted and escaped (a letter outside ASCII, "réar",
// breaks it as a control character does).
std::string cameraNameProblem(const std::string& name) {
  return "must be 1 to 63 letters, digits, '_' or '-' (a folder name; not \"intrinsics\", \"shards\" or \"slurm\"; got " + quote(name) + ")";
}

void readMount(JsonFields mount, DatasetCamera& camera) {
  const JsonFields::Range offset{-limits::kMaxMountOffset, limits::kMaxMountOffset, false, "m from the robot's centre"};
  camera.mount.x = mount.number("x", 0.0, offset);
  camera.mount.y = mount.number("y", 0.0, offset);
  camera.mount.yawDeg = mount.number("yaw_deg", 0.0, {-limits::kMaxMountYawDeg, limits::kMaxMountYawDeg, false, "degrees"});
  mount.finish();
}

void readCameras(const json& cameras, DatasetSpec& spec) {
  if (!cameras.is_array() || cameras.empty() || cameras.size() > static_cast<size_t>(limits::kMaxDatasetCameras))
    throw InputError(showPath(spec.file) + ": cameras: must be an array of 1 to " + std::to_string(limits::kMaxDatasetCameras) + " cameras");
  std::set<std::string> names;
  for (size_t i = 0; i < cameras.size(); ++i) {
    JsonFields c(cameras[i], spec.file, "cameras[" + std::to_string(i) + "]");
    DatasetCamera camera;
    camera.name = c.string("name");
    if (!isCameraFolderName(camera.name) || isReservedFolderName(camera.name)) c.fail("name", cameraNameProblem(camera.name));
    if (!names.insert(camera.name).second) c.fail("name", "duplicate camera name " + quote(camera.name));
    if (c.has("rig")) {
      camera.rig = c.raw("rig");
      rigFromJson(*camera.rig, spec.file, c.path("rig"));  // validated now, applied with the scene
    }
    if (auto mount = c.optionalObject("mount")) readMount(*mount, camera);
    c.finish();
    spec.cameras.push_back(std::move(camera));
  }
}

void readOutputs(JsonFields o, DatasetSpec& spec) {
  DatasetOutputs& out = spec.outputs;
  if (spec.layout == DatasetLayout::Multilayer && o.has("rgb"))
    o.fail("rgb", "the multilayer layout keeps the colour in each frame's OpenEXR (half, linear); leave rgb out");
  if (o.has("rgb") && !o.raw("rgb").is_string())  // the colour is always written: only its format is chosen
    o.fail("rgb", "must be \"png\" or \"exr\" (the colour is always written; got " + jsonTypeName(o.raw("rgb")) + ")");
  out.rgb = o.string("rgb", out.rgb);
  if (out.rgb != "png" && out.rgb != "exr") o.fail("rgb", "must be \"png\" or \"exr\"");
  for (OutputKind kind : switchableOutputs()) {
    const std::string name = outputName(kind);
    bool on = out.wanted.count(kind) > 0;
    if (outputRow(kind).classFilter && o.has(name) && o.raw(name).is_object()) {
      auto coco = o.optionalObject(name);
      on = true;
      const nlohmann::json& names = coco->raw("classes");
      if (!names.is_array() || names.empty() || names.size() > 1000)
        coco->fail("classes", "must be a list of 1 to 1000 class names");
      std::vector<std::string> classes;
      for (const auto& className : names) {
        if (!className.is_string()) coco->fail("classes", "must be a list of class names (strings)");
        classes.push_back(className.get<std::string>());
      }
      out.cocoClasses = classes;
      coco->finish();
    } else if (outputRow(kind).classFilter && o.has(name) && !o.raw(name).is_boolean()) {
      o.fail(name, "must be true, false or {\"classes\": [class names]} (got " + jsonTypeName(o.raw(name)) + ")");
    } else {
      on = o.boolean(name, on);
    }
    if (on) out.wanted.insert(kind);
    else out.wanted.erase(kind);
  }
  o.finish();
}

// The render request's settings (request_fields.h's rows with a JSON name; a dotted name lies in
// an object of its own), typed as JSON; their rules and messages are readRenderRequest's.
void readRequestField(JsonFields& object, const std::string& key, const RequestFieldRow& row, RequestFields& f) {
  if (!object.has(key)) return;
  switch (row.type) {
    case RequestFieldType::Text: f.set(row.field, object.string(key)); break;
    case RequestFieldType::Integer:
      // Any 64-bit integer reaches the request, whose rule speaks (as for the CLI's flag); a whole
      // number beyond 64 bits is told that rule too, not a range of the reader's own.
      f.set(row.field, object.integer(key, std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max(), row.range));
      break;
    case RequestFieldType::Number: f.set(row.field, object.number(key)); break;
    case RequestFieldType::Switch: f.set(row.field, object.boolean(key, false)); break;
  }
}

void readRequest(JsonFields& top, DatasetSpec& spec) {
  RequestFields f;
  std::map<std::string, std::vector<const RequestFieldRow*>> nested;  // by the object that holds them
  for (const RequestFieldRow& row : requestFieldRows()) {
    if (!row.json) continue;
    const std::string name = row.json;
    if (const size_t dot = name.find('.'); dot != std::string::npos) nested[name.substr(0, dot)].push_back(&row);
    else readRequestField(top, name, row, f);
  }
  for (const auto& [objectName, rows] : nested) {
    for (const RequestFieldRow* row : rows)  // written one level too high ("faces" for "mode_options.faces")
      if (const std::string leaf = std::string(row->json).substr(objectName.size() + 1); spec.json.contains(leaf))  // not top.has: that would make it a name typos are told to mean
        top.fail(leaf, "unknown field (did you mean " + std::string(row->json) + "?)");
    auto object = top.optionalObject(objectName);
    if (!object) continue;
    for (const RequestFieldRow* row : rows) readRequestField(*object, std::string(row->json).substr(objectName.size() + 1), *row, f);
    object->finish();
  }
  spec.request = readRenderRequest(f, RequestFieldNames::json(spec.file));
}

void readSampling(JsonFields& top, DatasetSpec& spec) {
  if (top.has("size")) {
    spec.size = top.integer("size", 360, limits::kMinImageSize, limits::kMaxImageSize);
    checkRenderSettings(spec.request.settings(RigSpec{}.resized(*spec.size)), settingNames(spec));  // size² × spp, before any scene is read
  }
  spec.frameIntervalSeconds =
      top.number("frame_interval_s", spec.frameIntervalSeconds, {0.0, limits::kMaxFrameIntervalSeconds, true, "s"});
}

}  // namespace

DatasetSpec loadDatasetSpec(const std::string& file) {
  std::string why;
  const auto text = readWholeFile(file, why, limits::kMaxJsonFileBytes);
  if (!text) throw InputError(showPath(file) + ": cannot open dataset spec (" + why + ")" + bundledFileHint(file, "docs/examples"));
  return datasetSpecFromText(*text, file);
}

DatasetSpec datasetSpecFromText(const std::string& text, const std::string& file) {
  DatasetSpec spec;
  spec.file = file;
  spec.sha256 = sha256OfBytes(text);
  spec.json = parseJsonText(text, file);
  JsonFields top(spec.json, file, "");
  if (const std::string format = top.string("format"); format != kDatasetSpecFormat)
    top.fail("format", "must be \"" + std::string(kDatasetSpecFormat) + "\"" + formatMismatchHint(format, kDatasetSpecFormat) +
                           (format == kSceneFormat ? "; a dataset spec names one in \"scene\"" : ""));
  top.string("description", "");
  if (top.has("comment")) top.raw("comment");
  const std::string scene = top.string("scene");
  if (scene.empty()) top.fail("scene", "must name a scene file");
  const fs::path scenePath(scene);
  spec.scene = scenePath.is_absolute() ? scene : (fs::path(file).parent_path() / scenePath).lexically_normal().string();
  if (spec.scene.empty()) spec.scene = scene;
  // Confinement is the user's to lift, not a downloaded file's (docs/robustness.md, "Threat model").
  if (top.boolean("allow_outside_files", false))
    top.fail("allow_outside_files", "a spec cannot let its scene pull in files from outside the scene's folder; "
                                    "whoever runs it can (omnicam dataset --allow-outside-files; Python: "
                                    "run_dataset(..., allow_outside_files=True))");
  readRequest(top, spec);
  readSampling(top, spec);
  // Cameras before poses: the frame limit counts camera-frames.
  if (top.has("cameras")) {
    readCameras(top.raw("cameras"), spec);
  } else {
    spec.cameras.push_back({"cam0", std::nullopt, 0.0, 0.0, 0.0});
  }
  readPoses(top.object("poses"), spec);
  if (auto motion = top.optionalObject("motion")) {
    if (spec.timing.kind != PathTiming::Kind::None)
      throw InputError(showPath(spec.file) + ": motion: timed waypoints (poses.speed_m_s or poses.timestamps_s) already give "
                       "every frame its velocity; leave motion out");
    readMotion(*motion, spec);
  }
  if (auto vibration = top.optionalObject("vibration")) readVibration(*vibration, spec);
  if (auto robot = top.optionalObject("robot")) {
    const std::vector<double> tilt =
        robot->numbers("tilt_deg", {0.0, 0.0}, {-limits::kMaxRigTiltDeg, limits::kMaxRigTiltDeg, false, "degrees"});
    spec.robotTiltDeg = {tilt[0], tilt[1]};
    robot->finish();
  }
  const auto layout = layoutNamed(top.string("layout", layoutName(spec.layout)));
  if (!layout) top.fail("layout", "must be \"files\" or \"multilayer\"");
  spec.layout = *layout;
  if (top.has("multilayer_compression")) {
    if (spec.layout != DatasetLayout::Multilayer) top.fail("multilayer_compression", "only with \"layout\": \"multilayer\"");
    const auto compression = compressionNamed(top.string("multilayer_compression"));
    if (!compression) top.fail("multilayer_compression", "must be \"rle\" or \"zip\"");
    spec.multilayerCompression = *compression;
  }
  if (auto outputs = top.optionalObject("outputs")) readOutputs(*outputs, spec);
  spec.euroc = top.boolean("euroc", false);
  if (spec.euroc) {
    if (spec.layout != DatasetLayout::Files) top.fail("euroc", "needs the files layout (EuRoC keeps one PNG per frame)");
    if (spec.outputs.rgb != "png") top.fail("euroc", "needs outputs.rgb \"png\" (EuRoC's images are PNG)");
    if (!(spec.frameIntervalSeconds * 1e9 >= 1.0))
      top.fail("euroc", "needs frame_interval_s of at least 1 ns (EuRoC names each image by its timestamp in ns)");
  }
  if (top.has("recording")) spec.recording = recordingCameraSpecFromJson(top.raw("recording"), file, "recording");
  if (auto calibration = top.optionalObject("calibration")) readCalibration(*calibration, spec);
  top.finish();
  return spec;
}

}  // namespace omnicam
