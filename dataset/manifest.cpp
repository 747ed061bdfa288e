#include "manifest.h"

#include <filesystem>

#include "atomic_file.h"
#include "dataset_spec.h"
#include "errors.h"
#include "json_fields.h"
#include "scene_loader.h"

namespace omnicam {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

json poseJson(const RobotPose& pose) { return {{"x", pose.x}, {"y", pose.y}, {"yaw_deg", pose.yawDeg}}; }

// Reading: every malformed piece is one InputError naming the manifest.
struct Reader {
  std::string file;
  [[noreturn]] void fail(const std::string& where, const std::string& what) const {
    throw InputError(showPath(file) + ": " + where + ": " + what);
  }
  const json& field(const json& object, const std::string& key, const std::string& where) const {
    if (!object.is_object()) fail(where, "must be an object");
    const auto it = object.find(key);
    if (it == object.end()) fail(where + "." + key, "missing");
    return *it;
  }
  double number(const json& object, const std::string& key, const std::string& where) const {
    const json& v = field(object, key, where);
    if (!v.is_number()) fail(where + "." + key, "must be a number");
    return v.get<double>();
  }
  std::string string(const json& object, const std::string& key, const std::string& where) const {
    const json& v = field(object, key, where);
    if (!v.is_string()) fail(where + "." + key, "must be a string");
    return v.get<std::string>();
  }
  RobotPose pose(const json& object, const std::string& key, const std::string& where) const {
    const json& p = field(object, key, where);
    const std::string at = where + "." + key;
    return {number(p, "x", at), number(p, "y", at), number(p, "yaw_deg", at)};
  }
  FileRecord fileRecord(const json& value, const std::string& where) const {
    FileRecord record{string(value, "path", where), string(value, "sha256", where)};
    // A manifest names files inside its own folder only.
    const fs::path p(record.path);
    if (record.path.empty() || p.is_absolute() || record.path.find("..") != std::string::npos)
      fail(where + ".path", "must be a relative path inside the dataset folder");
    if (record.sha256.size() != 64 || record.sha256.find_first_not_of("0123456789abcdef") != std::string::npos)
      fail(where + ".sha256", "must be 64 lowercase hex digits");
    return record;
  }
};

}  // namespace

json manifestToJson(const DatasetManifest& manifest) {
  json root = manifest.header;
  json frames = json::array();
  for (const auto& [index, frame] : manifest.frames) {
    json cameras = json::object();
    for (const auto& [name, camera] : frame.cameras) {
      json files = json::object();
      for (const auto& [kind, file] : camera.files) files[kind] = {{"path", file.path}, {"sha256", file.sha256}};
      cameras[name] = {{"pose", poseJson(camera.pose)}, {"files", files}};
    }
    frames.push_back({{"index", index}, {"timestamp", frame.timestamp}, {"pose", poseJson(frame.robot)},
                      {"cameras", cameras}});
  }
  root["frames"] = frames;
  return root;
}

json datasetIdentity(const json& header) {
  return {{"spec", header.at("spec")}, {"scene_sha256", header.at("scene").at("sha256")},
          {"engine", header.at("engine")}};
}

std::string shardManifestName(int index, int count) {
  return "shards/shard-" + std::to_string(index) + "-of-" + std::to_string(count) + ".json";
}

DatasetManifest readManifest(const std::string& dir, const std::string& name) {
  const std::string file = (fs::path(dir) / name).string();
  std::error_code ec;
  if (!fs::exists(file, ec)) throw InputError(showPath(dir) + ": not a dataset folder (no " + name + ")");
  json root = readJsonFile(file);
  const Reader r{file};
  if (!root.is_object() || r.string(root, "format", "manifest") != kManifestFormat)
    r.fail("format", std::string("must be \"") + kManifestFormat + "\"");
  DatasetManifest manifest;
  const json& frames = r.field(root, "frames", "manifest");
  if (!frames.is_array()) r.fail("frames", "must be an array");
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string where = "frames[" + std::to_string(i) + "]";
    const json& f = frames[i];
    FrameRecord frame;
    const json& index = r.field(f, "index", where);
    if (!index.is_number_integer() || index.get<long long>() < 0 || index.get<long long>() > 999999)
      r.fail(where + ".index", "must be an integer in [0, 999999]");
    frame.index = index.get<int>();
    frame.timestamp = r.number(f, "timestamp", where);
    frame.robot = r.pose(f, "pose", where);
    const json& cameras = r.field(f, "cameras", where);
    if (!cameras.is_object()) r.fail(where + ".cameras", "must be an object");
    for (auto it = cameras.begin(); it != cameras.end(); ++it) {
      const std::string at = where + ".cameras." + keySegment(it.key());
      CameraFrame camera;
      camera.pose = r.pose(it.value(), "pose", at);
      const json& files = r.field(it.value(), "files", at);
      if (!files.is_object()) r.fail(at + ".files", "must be an object");
      for (auto entry = files.begin(); entry != files.end(); ++entry)
        camera.files[entry.key()] = r.fileRecord(entry.value(), at + ".files." + keySegment(entry.key()));
      frame.cameras[it.key()] = std::move(camera);
    }
    if (!manifest.frames.emplace(frame.index, std::move(frame)).second)
      r.fail(where + ".index", "frame listed twice");
  }
  root.erase("frames");
  manifest.header = std::move(root);
  // The static files' records are checked like the frames'.
  const json& cameras = r.field(manifest.header, "cameras", "manifest");
  if (!cameras.is_array()) r.fail("cameras", "must be an array");
  for (size_t i = 0; i < cameras.size(); ++i) {
    const std::string where = "cameras[" + std::to_string(i) + "]";
    if (!isCameraFolderName(r.string(cameras[i], "name", where)))
      r.fail(where + ".name", "must be a camera folder name (letters, digits, '_' or '-')");
    const json& files = r.field(cameras[i], "files", where);
    if (!files.is_object()) r.fail(where + ".files", "must be an object");
    for (auto entry = files.begin(); entry != files.end(); ++entry)
      r.fileRecord(entry.value(), where + ".files." + keySegment(entry.key()));
  }
  return manifest;
}

void writeManifest(const std::string& dir, const DatasetManifest& manifest, const std::string& name) {
  writeTextAtomically((fs::path(dir) / name).string(), manifestToJson(manifest).dump(1) + "\n");
}

std::vector<FileRecord> manifestFiles(const DatasetManifest& manifest) {
  std::vector<FileRecord> files;
  for (const json& camera : manifest.header.at("cameras"))
    for (const auto& file : camera.at("files").items())
      files.push_back({file.value().at("path").get<std::string>(), file.value().at("sha256").get<std::string>()});
  for (const auto& [index, frame] : manifest.frames)
    for (const auto& [name, camera] : frame.cameras)
      for (const auto& [kind, file] : camera.files) files.push_back(file);
  return files;
}

}  // namespace omnicam
