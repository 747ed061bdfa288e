#pragma once
// DIR/manifest.json (docs/dataset-format.md): what the dataset is (spec and its hash, tool, engine,
// scene hash, cameras, class and instance tables) and every finished frame with its files and
// their SHA-256. Frames appear only once all their files are written; the manifest is rewritten
// atomically as frames complete, so a killed run always leaves a readable one.
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "dataset_spec.h"
#include "output_kinds.h"
#include "rig.h"
#include "file_formats.h"
#include "safe_files.h"

namespace omnicam {

inline constexpr const char* kManifestName = "manifest.json";
// A calibration sequence's Kalibr files beside the manifest (calibration_bag.h), listed in the
// header's calibration.files: the only files outside the cameras' folders.
inline constexpr const char* kKalibrBagPath = "kalibr.bag";
inline constexpr const char* kKalibrCamchainPath = "kalibr_camchain.yaml";

// Manifests are read whole, so bounded — by what the dataset limits let omnicam write
// (dataset_spec.h): a header (the spec as read, cameras, class and instance tables) of at most
// kMaxManifestHeaderBytes, checked before a run starts, and limits::kMaxCameraFrames entries of
// at most kMaxManifestBytesPerCameraFrame each (longest names and numbers: tested).
inline constexpr int64_t kMaxManifestHeaderBytes = int64_t{128} << 20;
inline constexpr int64_t kMaxManifestBytesPerCameraFrame = 5120;
inline constexpr int64_t kMaxManifestBytes =
    kMaxManifestHeaderBytes + limits::kMaxCameraFrames * kMaxManifestBytesPerCameraFrame;

struct FileRecord {
  std::string path;    // relative to the dataset folder, '/'-separated
  std::string sha256;
};

struct CameraFrame {
  RobotPose pose;  // the camera viewpoint's pose (mount applied)
  std::map<std::string, FileRecord> files;  // outputName(kind) → file
  // The rig this frame was rendered with, when it is not the camera's rig of the header: a
  // vibrating robot's (vibration.h).
  std::optional<RigSpec> rig;
  // The recording camera drawn for this frame and camera, when the spec's `recording` draws its
  // values (recording_camera_spec.h): every value, as recordFrame used it.
  std::optional<RecordingCamera> recording;

  // The file of `kind`, or null when the frame has none.
  const FileRecord* file(OutputKind kind) const {
    const auto at = files.find(outputName(kind));
    return at == files.end() ? nullptr : &at->second;
  }
};

struct FrameRecord {
  int index = 0;
  double timestamp = 0.0;
  RobotPose robot;        // at the exposure start (the timestamp)
  BodyVelocity velocity;  // the robot's, over the exposure (docs/motion.md)
  std::map<std::string, CameraFrame> cameras;  // camera name → its files
  RobotTilt robotTiltDeg{0.0, 0.0};            // the robot's tilt (placement.h); level unless it says
};

struct DatasetManifest {
  nlohmann::json header;              // everything but "frames" (see docs/dataset-format.md)
  std::map<int, FrameRecord> frames;  // finished frames by index
};

nlohmann::json manifestToJson(const DatasetManifest& manifest);
// A manifest from its text, strictly; `file` names it in messages (InputError naming the file and
// field). Every file record must name a file inside its camera's folder, every number lie in its
// range (forged manifests: exit 2). Reading one from a folder: readDatasetManifest (dataset_folder.h).
DatasetManifest manifestFromText(const std::string& text, const std::string& file);
// InputError naming the spec unless a manifest with this header stays within
// kMaxManifestHeaderBytes: called before a run writes anything.
void checkManifestHeaderSize(const nlohmann::json& header, const std::string& specFile);
void writeManifest(const SafeFolder& dir, const DatasetManifest& manifest, const std::string& name = kManifestName);
void writeManifest(const std::string& dir, const DatasetManifest& manifest, const std::string& name = kManifestName);

// What makes two runs the same dataset: the spec's content (not its formatting), the scene's
// bytes and the engine. Resuming or merging across any difference would mix frames.
// Its spec's "description" and any object's "comment" are words for people, not part of it.
nlohmann::json datasetIdentity(const nlohmann::json& header);
// What makes two headers' datasets differ, in words ("the spec's "spp", "size" differ; the
// scene's bytes differ"; one field "differs"), or "" when they are the same dataset. `a` is the
// earlier run's (the folder's), `b` the later's: a file only `b`'s scene reads is one it "now reads".
std::string identityDifference(const nlohmann::json& a, const nlohmann::json& b);

// At most this many shards (Slurm array tasks) per dataset: a count sizes work (a file and a
// task per shard) and is checked before any.
inline constexpr int kMaxShards = 100000;
// A shard's manifest, relative to the dataset folder: shards/shard-I-of-N.json.
std::string shardManifestName(int index, int count);
// The frames shard `index` of `count` renders of `totalFrames`: [F·I/N, F·(I+1)/N).
struct ShardFrames {
  int first = 0, end = 0;
};
ShardFrames shardFrames(int totalFrames, int index, int count);

// Every file the manifest lists (static files of each camera, then the frames'), for verifying.
std::vector<FileRecord> manifestFiles(const DatasetManifest& manifest);

}  // namespace omnicam
