#pragma once
// The dataset spec (format "omnicam-dataset/1", docs/dataset-format.md): which scene, engine and
// settings, which robot poses, which cameras on the robot, which outputs. Read strictly like a
// scene: unknown fields, wrong types and out-of-range values are InputErrors naming the field.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "calibration_sequence_spec.h"
#include "output_kinds.h"
#include "placement.h"
#include "recording_camera_spec.h"
#include "render_request.h"
#include "render_settings.h"
#include "rig.h"
#include "vibration.h"

namespace omnicam {

namespace limits {
// Frames of one dataset, and frames × cameras ("camera-frames"): each camera-frame is an entry of
// the manifest, which omnicam reads whole (manifest.h derives its size limit from these).
inline constexpr int kMaxDatasetFrames = 100000;
inline constexpr int kMaxDatasetCameras = 16;
inline constexpr int64_t kMaxCameraFrames = 100000;
// Camera mounts: offsets from the robot's centre (m) and turn (degrees).
inline constexpr double kMaxMountOffset = 100.0;
inline constexpr double kMaxMountYawDeg = 360.0;
// Random poses: the clearance (m) every pose keeps from every obstacle, and the seed (2^53:
// exact in every JSON reader).
inline constexpr double kMaxClearance = 100.0;
inline constexpr int64_t kMaxSeed = int64_t{1} << 53;
// Timestamp of frame i = i × interval (s): frameTimestampSeconds (output_kinds.h).
inline constexpr double kMaxFrameIntervalSeconds = 86400.0;
// Waypoint timestamps (poses.timestamps_s), seconds either side of 0: a year.
inline constexpr double kMaxTimestampSeconds = 3.2e7;
// Vibration amplitudes (docs/motion.md): a shaking robot, not a broken one.
inline constexpr double kMaxVibrationOffsetMm = 10.0;
inline constexpr double kMaxVibrationRotationDeg = 5.0;
inline constexpr double kMaxVibrationTiltDeg = 10.0;
}  // namespace limits

// One omnicam on the robot, standing on it where its mount says (placement.h): its viewpoint F'
// at the rig's height above the mount's point.
struct DatasetCamera {
  std::string name;                 // folder name: [A-Za-z0-9_-], 1–63 bytes
  std::optional<nlohmann::json> rig;  // the scene's rig format; absent: the scene's rig
  RobotMount mount;
};

// Robot poses drawn uniformly from a floor rectangle, kept only where F' is at least
// `clearance` metres from every obstacle's footprint (pose_sampler.h), yaw uniform in range.
struct RandomPoses {
  int count = 0;
  uint64_t seed = 0;
  double xMin = 0, yMin = 0, xMax = 0, yMax = 0;
  double clearance = 0.0;
  double yawMinDeg = -180.0, yawMaxDeg = 180.0;
};

struct DatasetOutputs {
  std::string rgb = "png";  // "png" or "exr" (files layout; multilayer: colour is in the frame EXR)
  // Besides the colour (output_kinds.h: each by its name, a boolean). COCO instances
  // annotations, one file per camera (docs/dataset-format.md): `true`, or {"classes": [names]}
  // (default: every class but floor, wall, ceiling and line).
  std::set<OutputKind> wanted = defaultOutputs();
  std::optional<std::vector<std::string>> cocoClasses;
};

enum class PoseSource { Path, List, Random };

enum class MotionSource { Still, Constant, BetweenPoses };

// A path's or list's poses as waypoints driven in time (trajectory.h, docs/motion.md): frames are
// then taken every frame_interval_s along them, each with the velocity it is driven at.
struct PathTiming {
  enum class Kind { None, Speed, Timestamps };
  Kind kind = Kind::None;
  double speed = 0.0, yawRateDegPerS = 0.0;  // Speed
  std::vector<double> timestamps;            // Timestamps: one per waypoint, strictly increasing
};

struct DatasetSpec {
  std::string file;       // the spec file
  std::string sha256;     // of its bytes
  nlohmann::json json;    // as read
  std::string scene;      // resolved against the spec's folder
  // Lifts the scene-folder rule (SceneLoadOptions): set only from the user's own
  // --allow-outside-files, never by the spec file (docs/robustness.md, "Threat model").
  bool allowOutsideFiles = false;
  // engine, mode and mode_options, spp, shading, timeout_s (render_request.h; threads come from
  // the run's --threads, not the spec)
  RenderRequest request;
  std::optional<int> size;  // overrides every camera's image size
  double frameIntervalSeconds = 0.1;  // timestamp of frame i = i · interval
  PoseSource poseSource = PoseSource::Path;
  std::string pathName;
  int pathFrames = 0;  // 0: the whole path
  std::vector<RobotPose> poseList;
  PathTiming timing;  // none: each pose is a frame
  RandomPoses random;
  std::vector<DatasetCamera> cameras;
  // The robot's body velocity over each frame's exposure (docs/motion.md): none (still), the
  // same for every frame, or the one that drives each pose to the next in frame_interval_s.
  MotionSource motion = MotionSource::Still;
  BodyVelocity velocity;
  // Every frame's rig shaken within these amplitudes (vibration.h); none: the rigs as given.
  Vibration vibration;
  // The robot's own tilt (roll, pitch; degrees): every camera on it tilted alike, about the
  // robot's origin on the floor (placement.h). Each rig's tilt_deg tilts that camera alone.
  RobotTilt robotTiltDeg{0.0, 0.0};
  // files: one file per output and frame; multilayer: one OpenEXR per frame and camera
  // (output_kinds.h).
  DatasetLayout layout = DatasetLayout::Files;
  // multilayer only: "rle" (fast, larger) or "zip" (deflate level 1: half the size, slower);
  // docs/performance.md, "Datasets".
  FrameCompression multilayerCompression = FrameCompression::Rle;
  DatasetOutputs outputs;
  // Each camera's colour frames also in the EuRoC/ASL layout (euroc_files.h): <camera>/data/<t_ns>.png
  // instead of <camera>/rgb/NNNNNN.png, with <camera>/data.csv and <camera>/sensor.yaml.
  bool euroc = false;
  // What a real camera would record (recording_camera.h), applied to every RGB frame; none: the
  // renderer's image as it is.
  std::optional<RecordingCameraSpec> recording;
  // A calibration sequence (calibration_sequence.h): the robot stands at its one pose while the
  // scene's target is held at one pose per frame; none: the scene as it is.
  std::optional<CalibrationSequenceSpec> calibration;
};

// A camera name is a folder name: 1–63 letters, digits, '_' or '-', not "intrinsics" (what
// manifests hold). A new spec's may also not be the dataset folder's own "shards" or "slurm"
// (isReservedFolderName); datasets written before that rule still read.
bool isCameraFolderName(const std::string& name);
bool isReservedFolderName(const std::string& name);

// InputError naming the spec's `field` unless `frames` frames of every camera stay within
// limits::kMaxDatasetFrames and limits::kMaxCameraFrames.
void checkFrameCount(const DatasetSpec& spec, size_t frames, const std::string& field);
// How render-setting messages name the spec's fields ("spec.json: spp").
SettingNames settingNames(const DatasetSpec& spec);

DatasetSpec loadDatasetSpec(const std::string& file);
DatasetSpec datasetSpecFromText(const std::string& text, const std::string& file);


}  // namespace omnicam
