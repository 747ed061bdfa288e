#include "manifest.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "atomic_file.h"
#include "dataset_spec.h"
#include "errors.h"
#include "file_confinement.h"
#include "json_fields.h"
#include "output_kinds.h"
#include "render_settings.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "sidecar.h"

namespace omnicam {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {


// Reading: every malformed piece is one InputError naming the manifest and the field.

bool isSha256(const std::string& text) {
  return text.size() == 64 && text.find_first_not_of("0123456789abcdef") == std::string::npos;
}

// A file of camera folder `camera` as omnicam names them: "<camera>/<name>" or
// "<camera>/<kind>/<name>", every name letters, digits, '_', '-' or '.' and not starting with
// '.' (so no "..", no hidden file, no temporary). Anything else could point outside the dataset
// or at a file of another camera.
bool isCameraFilePath(const std::string& path, const std::string& camera) {
  if (path.size() > 255 || path.compare(0, camera.size() + 1, camera + "/") != 0) return false;
  size_t names = 0;
  for (size_t begin = camera.size() + 1; begin <= path.size(); ++names) {
    const size_t end = std::min(path.find('/', begin), path.size());
    const std::string name = path.substr(begin, end - begin);
    if (name.empty() || name[0] == '.' ||
        name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.") != std::string::npos)
      return false;
    begin = end + 1;
  }
  return names == 1 || names == 2;
}

FileRecord readFileRecord(JsonFields f, const std::string& camera) {
  FileRecord record{f.string("path"), f.string("sha256")};
  if (!isCameraFilePath(record.path, camera))
    f.fail("path", "must be a file in the dataset's camera folder " + showPath(camera) + " (got " + quote(record.path) + ")");
  if (!isSha256(record.sha256)) f.fail("sha256", "must be 64 lowercase hex digits");
  f.finish();
  return record;
}

// The "files" object of a camera → records, each inside `camera`; a frame's keys are the kinds
// of frame files, a camera's static files may have any key.
std::map<std::string, FileRecord> readFileRecords(JsonFields& parent, const std::string& camera, bool frameKinds) {
  const json& raw = parent.raw("files");
  JsonFields files = parent.object("files");
  std::map<std::string, FileRecord> records;
  for (auto it = raw.begin(); it != raw.end(); ++it) {
    if (frameKinds && !outputNamed(it.key())) files.fail(it.key(), "unknown kind of frame file");
    records[it.key()] = readFileRecord(files.object(it.key()), camera);
  }
  files.finish();
  return records;
}

RobotPose readManifestPose(JsonFields p) {
  const RobotPose pose{p.number("x"), p.number("y"), p.number("yaw_deg")};
  checkPose(pose, showPath(p.file()) + ": " + p.where());
  p.finish();
  return pose;
}

void requireHash(JsonFields& f, const std::string& key) {
  if (!isSha256(f.string(key))) f.fail(key, "must be 64 lowercase hex digits");
}

// scene.inputs: the files the scene read beyond its own text, each {"path", "sha256"}. Absent in
// manifests written before omnicam recorded them: then none are known.
void checkSceneInputs(JsonFields& scene) {
  if (!scene.has("inputs")) return;
  const json& inputs = scene.raw("inputs");
  if (!inputs.is_array()) scene.fail("inputs", "must be an array of {\"path\", \"sha256\"}");
  std::set<std::string> paths;
  for (size_t i = 0; i < inputs.size(); ++i) {
    JsonFields input(inputs[i], scene.file(), scene.where() + ".inputs[" + std::to_string(i) + "]");
    const std::string path = input.string("path");
    if (path.empty() || path.size() > 4096) input.fail("path", "must be 1 to 4096 bytes long");
    if (!paths.insert(path).second) input.fail("path", "lists " + quote(path) + " twice");
    requireHash(input, "sha256");
    input.finish();
  }
}

// What frames are checked against: the header's cameras and frame count.
struct HeaderFacts {
  std::set<std::string> cameras;
  int64_t frameCount = 0;
};

// The outputs' fields that gathering annotations reads back: the layout, the outputs written and
// the COCO classes.
void checkOutputs(JsonFields outputs) {
  if (outputs.has("layout") && !layoutNamed(outputs.string("layout"))) outputs.fail("layout", "must be \"files\" or \"multilayer\"");
  const json& written = outputs.has("written") ? outputs.raw("written") : json::array();
  if (!written.is_array()) outputs.fail("written", "must be a list of output names");
  for (const json& name : written)
    if (!name.is_string() || !outputNamed(name.get<std::string>()) || name == outputName(OutputKind::Multilayer))
      outputs.fail("written", "must be a list of output names (got " + quote(name.dump()) + ")");
  if (outputs.has("coco_classes")) {
    const json& classes = outputs.raw("coco_classes");
    if (!classes.is_array()) outputs.fail("coco_classes", "must be a list of class ids");
    for (const json& id : classes)
      if (!id.is_number_integer() || id.get<int64_t>() < 1 || id.get<int64_t>() > 65535)
        outputs.fail("coco_classes", "must be a list of class ids (1 to 65535)");
  }
  if (outputs.has("coco_keypoints")) {
    const json& keypoints = outputs.raw("coco_keypoints");
    if (!keypoints.is_array()) outputs.fail("coco_keypoints", "must be a list of landmark names");
    for (const json& name : keypoints)
      if (!name.is_string()) outputs.fail("coco_keypoints", "must be a list of landmark names");
  }
}

// The header's fields that omnicam reads back (the rest it only carries along).
HeaderFacts checkHeader(JsonFields& top) {
  if (top.string("format") != kManifestFormat) top.fail("format", std::string("must be \"") + kManifestFormat + "\"");
  top.object("spec");
  top.object("engine");
  requireHash(top, "spec_sha256");
  JsonFields scene = top.object("scene");
  requireHash(scene, "sha256");
  checkSceneInputs(scene);
  const int64_t frameCount = top.integer("frame_count", 0, limits::kMaxDatasetFrames);
  if (!top.raw("complete").is_boolean()) top.fail("complete", "must be true or false");
  if (auto shard = top.optionalObject("shard")) {
    const int64_t count = shard->integer("count", 1, kMaxShards);
    shard->integer("index", 0, count - 1);
    const int64_t first = shard->integer("first_frame", 0, frameCount);
    shard->integer("end_frame", first, frameCount);
    shard->finish();
  }
  if (auto outputs = top.optionalObject("outputs")) checkOutputs(*outputs);
  if (top.has("classes")) {
    const json& classes = top.raw("classes");
    if (!classes.is_array()) top.fail("classes", "must be a list of {\"id\", \"name\"}");
    for (const json& c : classes)
      if (!c.is_object() || !c.contains("id") || !c.at("id").is_number_integer() || !c.contains("name") ||
          !(c.at("name").is_string() || c.at("name").is_null()))
        top.fail("classes", "must be a list of {\"id\", \"name\"} (integer id, string or null name)");
  }
  const json& cameras = top.raw("cameras");
  if (!cameras.is_array() || cameras.empty() || cameras.size() > static_cast<size_t>(limits::kMaxDatasetCameras))
    top.fail("cameras", "must be an array of 1 to " + std::to_string(limits::kMaxDatasetCameras) + " cameras");
  HeaderFacts facts{{}, frameCount};
  for (size_t i = 0; i < cameras.size(); ++i) {
    JsonFields c(cameras[i], top.file(), "cameras[" + std::to_string(i) + "]");
    const std::string name = c.string("name");
    if (!isCameraFolderName(name)) c.fail("name", "must be a camera folder name (letters, digits, '_' or '-')");
    if (!facts.cameras.insert(name).second) c.fail("name", "duplicate camera name " + quote(name));
    readFileRecords(c, name, false);
  }
  return facts;
}

FrameRecord readFrame(JsonFields f, const HeaderFacts& header) {
  FrameRecord frame;
  if (header.frameCount == 0) f.fail("index", "the manifest's frame_count is 0");
  frame.index = static_cast<int>(f.integer("index", 0, header.frameCount - 1));
  frame.timestamp = f.number("timestamp");
  frame.robot = readManifestPose(f.object("pose"));
  if (auto velocity = f.optionalObject("velocity")) {
    const JsonFields::Range speed{-limits::kMaxSpeed, limits::kMaxSpeed, false, "m/s"};
    frame.velocity.vx = velocity->number("vx", speed);
    frame.velocity.vy = velocity->number("vy", speed);
    frame.velocity.yawRateDegPerS =
        velocity->number("yaw_rate_deg_per_s", {-limits::kMaxYawRateDegPerS, limits::kMaxYawRateDegPerS, false, "degrees/s"});
    velocity->finish();
  }
  if (f.has("robot_tilt_deg")) {
    const std::vector<double> tilt =
        f.numbers("robot_tilt_deg", {0.0, 0.0}, {-limits::kMaxRigTiltDeg - limits::kMaxVibrationTiltDeg,
                                                 limits::kMaxRigTiltDeg + limits::kMaxVibrationTiltDeg, false, "degrees"});
    frame.robotTiltDeg = {tilt[0], tilt[1]};
  }
  const json& raw = f.raw("cameras");
  JsonFields cameras = f.object("cameras");
  for (auto it = raw.begin(); it != raw.end(); ++it) {
    if (!header.cameras.count(it.key())) cameras.fail(it.key(), "not a camera of the manifest's cameras");
    JsonFields camera = cameras.object(it.key());
    CameraFrame cameraFrame{readManifestPose(camera.object("pose")), readFileRecords(camera, it.key(), true), std::nullopt, std::nullopt};
    if (camera.has("rig")) cameraFrame.rig = rigFromJson(camera.raw("rig"), f.file(), camera.path("rig"));
    if (camera.has("recording")) cameraFrame.recording = recordingCameraFromJson(camera.raw("recording"), f.file(), camera.path("recording"));
    camera.finish();
    frame.cameras[it.key()] = std::move(cameraFrame);
  }
  cameras.finish();
  f.finish();
  return frame;
}

}  // namespace

json manifestToJson(const DatasetManifest& manifest) {
  json root = manifest.header;
  json frames = json::array();
  for (const auto& [index, frame] : manifest.frames) {
    json cameras = json::object();
    for (const auto& [name, camera] : frame.cameras) {
      json files = json::object();
      for (const auto& [kind, file] : camera.files) files[kind] = {{"path", file.path}, {"sha256", file.sha256}};
      cameras[name] = {{"pose", footPoseToJson(camera.pose)}, {"files", files}};
      if (camera.rig) cameras[name]["rig"] = rigToJson(*camera.rig);
      if (camera.recording) cameras[name]["recording"] = recordingCameraToJson(*camera.recording);
    }
    json entry = {{"index", index}, {"timestamp", frame.timestamp}, {"pose", poseToJson(frame.robot)}, {"cameras", cameras}};
    if (!frame.velocity.still())  // the pose is then the exposure start's (docs/motion.md)
      entry["velocity"] = {{"vx", frame.velocity.vx}, {"vy", frame.velocity.vy}, {"yaw_rate_deg_per_s", frame.velocity.yawRateDegPerS}};
    if (frame.robotTiltDeg != RobotTilt{0.0, 0.0}) entry["robot_tilt_deg"] = frame.robotTiltDeg;
    frames.push_back(std::move(entry));
  }
  root["frames"] = frames;
  return root;
}

namespace {

// `value` without the "comment" of any object in it (JsonFields lets every object have one).
json withoutComments(json value) {
  if (value.is_object()) {
    value.erase("comment");
    for (auto& [key, inner] : value.items()) inner = withoutComments(std::move(inner));
  } else if (value.is_array()) {
    for (json& inner : value) inner = withoutComments(std::move(inner));
  }
  return value;
}

}  // namespace

json datasetIdentity(const json& header) {
  // Words for people: a new description or comment is the same dataset.
  json spec = withoutComments(header.at("spec"));
  if (spec.is_object()) spec.erase("description");
  // A manifest written before omnicam recorded the scene's files has no "inputs": null, compared
  // with nothing (what it rendered from cannot be told).
  return {{"spec", spec},
          {"scene_sha256", header.at("scene").at("sha256")},
          {"scene_inputs", header.at("scene").value("inputs", json())},
          {"engine", header.at("engine")}};
}

namespace {

// "\"a.png\"", "\"a.png\", \"b.png\"", "\"b\", \"c\", \"d\" and 2 more": at most three named.
std::string someNames(const std::set<std::string>& names) {
  std::string named;
  size_t shown = 0;
  for (const std::string& name : names) {
    if (shown++ == 3) break;
    named += (named.empty() ? "" : ", ") + quote(name);
  }
  if (names.size() > 3) named += " and " + std::to_string(names.size() - 3) + " more";
  return named;
}

// The scene's files (beyond its own text) that `earlier`'s run and `later`'s both read with other
// bytes ("the scene's file "a.png" differs"), that only the later run reads ("the scene now reads
// "b.png""), and that only the earlier one read ("no longer reads").
std::string sceneInputsDifference(const json& earlier, const json& later) {
  std::map<std::string, std::string> x, y;
  for (const json& input : earlier) x[input.at("path").get<std::string>()] = input.at("sha256").get<std::string>();
  for (const json& input : later) y[input.at("path").get<std::string>()] = input.at("sha256").get<std::string>();
  std::set<std::string> changed, added, dropped;
  for (const auto& [path, hash] : x)
    if (!y.count(path)) dropped.insert(path);
    else if (y.at(path) != hash) changed.insert(path);
  for (const auto& [path, hash] : y)
    if (!x.count(path)) added.insert(path);
  if (changed.empty() && added.empty() && dropped.empty()) return "";
  std::vector<std::string> parts;
  if (!changed.empty())
    parts.push_back("the scene's " + std::string(changed.size() == 1 ? "file " : "files ") + someNames(changed) +
                    (changed.size() == 1 ? " differs" : " differ"));
  if (!added.empty()) parts.push_back("the scene now reads " + someNames(added));
  if (!dropped.empty()) parts.push_back("the scene no longer reads " + someNames(dropped));
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : "; ") + part;
  return text + " (its textures, environment or glTF files)";
}

}  // namespace

std::string identityDifference(const json& a, const json& b) {
  const json x = datasetIdentity(a), y = datasetIdentity(b);
  std::vector<std::string> parts;
  const json &specX = x.at("spec"), &specY = y.at("spec");
  if (specX != specY) {
    std::vector<std::string> fields;
    if (specX.is_object() && specY.is_object()) {
      std::set<std::string> keys;
      for (const auto& [key, value] : specX.items()) keys.insert(key);
      for (const auto& [key, value] : specY.items()) keys.insert(key);
      for (const std::string& key : keys)
        if (specX.value(key, json()) != specY.value(key, json())) fields.push_back(quote(key));
    }
    std::string named;
    for (const std::string& field : fields) named += (named.empty() ? "" : ", ") + field;
    parts.push_back(fields.empty() ? "the spec differs" : "the spec's " + named + (fields.size() == 1 ? " differs" : " differ"));
  }
  if (x.at("scene_sha256") != y.at("scene_sha256")) parts.push_back("the scene's bytes differ");
  if (!x.at("scene_inputs").is_null() && !y.at("scene_inputs").is_null())
    if (const std::string files = sceneInputsDifference(x.at("scene_inputs"), y.at("scene_inputs")); !files.empty())
      parts.push_back(files);
  if (x.at("engine") != y.at("engine")) parts.push_back("the engine differs");
  std::string text;
  for (const std::string& part : parts) text += (text.empty() ? "" : "; ") + part;
  return text;
}

std::string shardManifestName(int index, int count) {
  return "shards/shard-" + std::to_string(index) + "-of-" + std::to_string(count) + ".json";
}

ShardFrames shardFrames(int totalFrames, int index, int count) {
  return {static_cast<int>(static_cast<int64_t>(totalFrames) * index / count),
          static_cast<int>(static_cast<int64_t>(totalFrames) * (index + 1) / count)};
}

// Each frame file where omnicam names it (isFramePath), and no file two records': a forged
// manifest that points every frame at one image would otherwise verify, and compare one frame as
// many.
void checkFramePaths(const DatasetManifest& manifest, const std::string& file) {
  std::map<std::string, std::string> owners;  // path → the record that names it
  for (const auto& [index, frame] : manifest.frames)
    for (const auto& [camera, files] : frame.cameras)
      for (const auto& [kind, record] : files.files) {
        const std::string where = "frame " + std::to_string(index) + " camera " + quote(camera) + " " + quote(kind);
        const std::optional<OutputKind> outputKind = outputNamed(kind);  // readFileRecords checked the name
        if (!outputKind || !isFramePath(record.path, camera, *outputKind, index)) {
          FrameOutputPlan plan;
          throw InputError(showPath(file) + ": " + where + ": " + quote(record.path) + " is not where omnicam names that file (" +
                           (outputKind ? plan.framePath(camera, *outputKind, index) : camera + "/" + kind + "/…") + ")");
        }
        const auto [owner, fresh] = owners.emplace(record.path, where);
        if (!fresh) throw InputError(showPath(file) + ": " + where + ": " + quote(record.path) + " is " + owner->second + "'s file too");
      }
}

DatasetManifest manifestFromText(const std::string& text, const std::string& file) {
  // A manifest holds its spec one level down.
  json root = parseJsonText(text, file, limits::kMaxJsonDepth + 1);
  JsonFields top(root, file, "");
  const HeaderFacts header = checkHeader(top);
  const json& frames = top.raw("frames");
  if (!frames.is_array()) top.fail("frames", "must be an array");
  DatasetManifest manifest;
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string where = "frames[" + std::to_string(i) + "]";
    FrameRecord frame = readFrame(JsonFields(frames[i], file, where), header);
    const int index = frame.index;
    if (!manifest.frames.emplace(index, std::move(frame)).second)
      throw InputError(showPath(file) + ": " + where + ".index: frame " + std::to_string(index) + " listed twice");
  }
  checkFramePaths(manifest, file);
  root.erase("frames");
  manifest.header = std::move(root);
  return manifest;
}

void checkManifestHeaderSize(const nlohmann::json& header, const std::string& specFile) {
  const size_t bytes = header.dump(1).size();
  if (bytes > static_cast<size_t>(kMaxManifestHeaderBytes))
    throw InputError(showPath(specFile) + ": the dataset's manifest would start with " + std::to_string(bytes) +
                     " bytes (the spec as read, cameras, classes, instances); the limit is " +
                     std::to_string(kMaxManifestHeaderBytes));
}

void writeManifest(const SafeFolder& dir, const DatasetManifest& manifest, const std::string& name) {
  // Written without following links inside the dataset folder (safe_files.h).
  dir.writeFile(name, manifestToJson(manifest).dump(1) + "\n", Durability::Synced);
}

void writeManifest(const std::string& dir, const DatasetManifest& manifest, const std::string& name) {
  writeManifest(SafeFolder(dir), manifest, name);
}

std::vector<FileRecord> manifestFiles(const DatasetManifest& manifest) {
  std::vector<FileRecord> files;
  // A calibration sequence's Kalibr files beside the manifest (calibration_bag.h): only their
  // fixed names, never a path of the manifest's choosing.
  const json calibration = manifest.header.value("calibration", json::object());
  if (calibration.is_object() && calibration.contains("files")) {
    const json& listed = calibration.at("files");
    if (!listed.is_object()) throw InputError(std::string(kManifestName) + ": calibration.files: must be an object");
    for (const auto& file : listed.items()) {
      const json& record = file.value();
      const std::string where = std::string(kManifestName) + ": calibration.files." + file.key();
      if (!record.is_object() || !record.contains("path") || !record.contains("sha256") || !record.at("sha256").is_string() ||
          !isSha256(record.at("sha256").get<std::string>()))
        throw InputError(where + ": must be {\"path\", \"sha256\"} (64 lowercase hex digits)");
      if (record.at("path") != kKalibrBagPath && record.at("path") != kKalibrCamchainPath)
        throw InputError(where + ".path: must be \"" + kKalibrBagPath + "\" or \"" + kKalibrCamchainPath + "\"");
      files.push_back({record.at("path").get<std::string>(), record.at("sha256").get<std::string>()});
    }
  }
  for (const json& camera : manifest.header.at("cameras"))
    for (const auto& file : camera.at("files").items())
      files.push_back({file.value().at("path").get<std::string>(), file.value().at("sha256").get<std::string>()});
  for (const auto& [index, frame] : manifest.frames)
    for (const auto& [name, camera] : frame.cameras)
      for (const auto& [kind, file] : camera.files) files.push_back(file);
  return files;
}

}  // namespace omnicam
