// The dataset's entry points (fuzz_entries.h): spec, manifest, shard manifest.
#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "dataset_folder.h"
#include "dataset_shards.h"
#include "dataset_spec.h"
#include "errors.h"
#include "fuzz_entries.h"
#include "manifest.h"
#include "recording_camera_spec.h"
#include "render_settings.h"
#include "scene_loader.h"

namespace omnicam::fuzz {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

std::string text(const uint8_t* data, size_t size) { return std::string(reinterpret_cast<const char*>(data), size); }

// A failed invariant: not an InputError, so the fuzzer reports it.
[[noreturn]] void finding(const std::string& what) { throw std::logic_error("fuzz finding: " + what); }

// One scratch folder per process (TMPDIR, else /dev/shm, whose fsync costs nothing), removed at
// exit; each input gets it empty. A process that crashed cannot remove its own: the next one
// removes those whose process is gone (their names carry the pid).
class ScratchFolder {
 public:
  ScratchFolder() {
    const char* tmp = std::getenv("TMPDIR");
    const std::string base = tmp && *tmp ? tmp : fs::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
    const std::string prefix = "omnicam-fuzz-shards-";
    std::error_code ec;
    for (auto it = fs::directory_iterator(base, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) {
      const std::string entry = it->path().filename().string();
      if (entry.rfind(prefix, 0) != 0) continue;
      const long pid = std::strtol(entry.c_str() + prefix.size(), nullptr, 10);
      std::error_code ignored;
      if (pid > 0 && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove_all(it->path(), ignored);
    }
    std::string name = base + "/" + prefix + std::to_string(getpid()) + "-XXXXXX";
    if (!mkdtemp(name.data())) throw std::runtime_error("fuzz: cannot create a scratch folder in " + base);
    path_ = name;
  }
  ~ScratchFolder() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  // An empty dataset folder with an empty shards/ in it.
  std::string fresh() const {
    const fs::path dir = path_ / "dataset";
    fs::remove_all(dir);
    fs::create_directories(dir / "shards");
    return dir.string();
  }

 private:
  fs::path path_;
};

const ScratchFolder& scratch() {
  static const ScratchFolder folder;
  return folder;
}

}  // namespace

void datasetSpec(const uint8_t* data, size_t size) {
  DatasetSpec spec;
  try {
    spec = datasetSpecFromText(text(data, size), assetsDir() + "/spec.json");
    // What runDataset checks before it reads the scene (a camera without a rig: the default).
    checkManifestHeaderSize(json{{"spec", spec.json}, {"spec_file", spec.file}, {"spec_sha256", spec.sha256}}, spec.file);
    for (const DatasetCamera& camera : spec.cameras) {
      RigSpec rig = camera.rig ? rigFromJson(*camera.rig, spec.file, "cameras." + camera.name + ".rig") : RigSpec{};
      if (spec.size) rig = rig.resized(*spec.size);  // as cameraSetups (dataset_plan.cpp) sizes it
      checkRenderSettings(spec.request.settings(rig), settingNames(spec));
      (void)rig.camera();
      SettingNames names;
      names.pose = showPath(spec.file) + ": poses";
      for (const RobotPose& robot : spec.poseList) checkPlacement(CameraPlacement(robot, {}, camera.mount), names);
    }
  } catch (const InputError&) {
    return;
  }
  // The manifest carries the recording as omnicam writes it: it must read back.
  if (spec.recording) {
    try {
      if (recordingCameraSpecFromJson(recordingCameraSpecToJson(*spec.recording), spec.file, "recording") != *spec.recording)
        finding("a recording omnicam read reads back as another");
      (void)recordingCameraFromJson(recordingCameraToJson(spec.recording->draw(0)), spec.file, "recording");
    } catch (const InputError& e) {
      finding(std::string("a recording omnicam read does not read back: ") + e.what());
    }
  }
}

void manifest(const uint8_t* data, size_t size) {
  const std::string file = "fuzz/manifest.json";
  DatasetManifest read;
  try {
    read = manifestFromText(text(data, size), file);
  } catch (const InputError&) {
    return;
  }
  // What --verify and a resumed run do next with it.
  (void)manifestFiles(read);
  if (!identityDifference(read.header, read.header).empty()) finding("a manifest's dataset differs from itself");
  // A resumed run rewrites the manifest it read (writeManifest): omnicam must read that back.
  try {
    const DatasetManifest again = manifestFromText(manifestToJson(read).dump(1) + "\n", file);
    if (again.frames.size() != read.frames.size()) finding("the rewritten manifest lists another number of frames");
  } catch (const InputError& e) {
    finding(std::string("a manifest omnicam read and rewrote does not read back: ") + e.what());
  }
}

void shardManifest(const uint8_t* data, size_t size) {
  const std::string bytes = text(data, size);
  int index = 0, count = 1;
  try {
    const DatasetManifest read = manifestFromText(bytes, "fuzz/shards/shard-0-of-1.json");
    if (read.header.contains("shard")) {
      index = read.header.at("shard").at("index").get<int>();
      count = read.header.at("shard").at("count").get<int>();
    }
  } catch (const InputError&) {
    return;  // the folder's readers below read it with the same reader
  }
  // A count sizes the work (one manifest per shard looked up): large ones only through the reader.
  if (count > 64) return;
  const std::string dir = scratch().fresh();
  const std::string name = shardManifestName(index, count);
  std::ofstream(fs::path(dir) / name, std::ios::binary) << bytes;
  try {
    (void)shardCountsIn(dir);
    (void)shardStates(dir, count, false);  // --status
    (void)shardStates(dir, count, true);   // --status --verify (its files are missing)
    (void)mergeDatasetShards(dir, count);  // --merge
  } catch (const InputError&) {
    return;
  }
  // The merge wrote DIR/manifest.json: omnicam must read it back.
  try {
    (void)readDatasetManifest(dir);
  } catch (const InputError& e) {
    finding(std::string("a merged manifest does not read back: ") + e.what());
  }
}

}  // namespace omnicam::fuzz
