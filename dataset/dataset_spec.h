#pragma once
// The dataset spec (format "omnicam-dataset/1", docs/dataset-format.md): which scene, engine and
// settings, which robot poses, which cameras on the robot, which outputs. Read strictly like a
// scene: unknown fields, wrong types and out-of-range values are InputErrors naming the field.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "recording_camera.h"
#include "render_settings.h"
#include "rig.h"

namespace omnicam {

// One omnicam on the robot. Its viewpoint F' sits at (mountX, mountY) in the robot frame, at the
// rig's height above the floor, turned by mountYawDeg.
struct DatasetCamera {
  std::string name;                 // folder name: [A-Za-z0-9_-], 1–63 bytes
  std::optional<nlohmann::json> rig;  // the scene's rig format; absent: the scene's rig
  double mountX = 0.0, mountY = 0.0, mountYawDeg = 0.0;
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
  std::string rgb = "png";  // "png" or "exr"
  bool depth = true, instance = true, semantic = true, normal = true, landmarks = true;
};

enum class PoseSource { Path, List, Random };

struct DatasetSpec {
  std::string file;       // the spec file
  std::string sha256;     // of its bytes
  nlohmann::json json;    // as read
  std::string scene;      // resolved against the spec's folder
  bool allowOutsideFiles = false;
  std::string engine = "fast";
  std::string mode = "exact";
  int faces = 6, faceSize = 512, polygons = 1024;
  int spp = 1;
  Shading shading = Shading::Unlit;
  std::optional<int> size;  // overrides every camera's image size
  double timeoutSeconds = 600.0;
  double frameIntervalSeconds = 0.1;  // timestamp of frame i = i · interval
  PoseSource poseSource = PoseSource::Path;
  std::string pathName;
  int pathFrames = 0;  // 0: the whole path
  std::vector<RobotPose> poseList;
  RandomPoses random;
  std::vector<DatasetCamera> cameras;
  DatasetOutputs outputs;
  // What a real camera would record (recording_camera.h), applied to every RGB frame; none: the
  // renderer's image as it is.
  std::optional<RecordingCamera> recording;
};

// A camera name is a folder name: 1–63 letters, digits, '_' or '-', not "intrinsics".
bool isCameraFolderName(const std::string& name);

DatasetSpec loadDatasetSpec(const std::string& file);
DatasetSpec datasetSpecFromText(const std::string& text, const std::string& file);

// The world pose of a camera's viewpoint for a robot pose (the mount applied).
RobotPose cameraPose(const DatasetCamera& camera, const RobotPose& robot);

}  // namespace omnicam
