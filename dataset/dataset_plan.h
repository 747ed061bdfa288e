#pragma once
// What one run of a dataset spec will write, decided before anything is written: the scene, the
// cameras with their rigs and models, the robot poses, the engine, the frames of this run (all,
// or a shard's), each frame's outputs and layout, the manifest's header, each camera's static
// files (intrinsics, poses) and the folders. frame_scheduler.h renders it; dataset_runner.h
// decides what the folder keeps.
#include <algorithm>
#include <memory>
#include <optional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "camera.h"
#include "dataset_options.h"
#include "dataset_spec.h"
#include "engines.h"
#include "output_kinds.h"
#include "ray_scene.h"
#include "scene_ids.h"

namespace omnicam {

struct CameraSetup {
  const DatasetCamera* camera;
  RigSpec rig;
  std::shared_ptr<const Camera> model;  // the rig's camera (make_camera.h), built once per run
};

// The frames [first, end) one run renders, listed in manifestName.
struct FrameRange {
  bool sharded = false;
  int first = 0, end = 0;
  std::string manifestName;
};

// A camera's file that stays the same from frame to frame (intrinsics, poses): its key in the
// manifest, its path and its text.
struct StaticFile {
  std::string key, relative, text;
};

// A frame's own scene when frames differ in more than the camera's placement (a calibration
// sequence moves its target): the scene, its engine and its landmark rays. Built in place.
struct FrameWorld {
  Scene scene;
  std::unique_ptr<Engine> engine;
  std::unique_ptr<RayScene> rays;  // when the outputs annotate landmarks
};

// A calibration sequence (spec.calibration): the scene's target it moves, and the target's pose
// in the world and in the first camera's viewpoint frame in every frame.
struct CalibrationSequence {
  int target = -1;
  std::vector<Rigid> worldFromTarget, viewpointFromTarget;
};

// Decided once, in the constructor, and read only after: every accessor is const. The engine is
// the run's one moving part (rendering changes its state: a ground truth's session, its version
// read once). Built in place and never moved: the engine and the landmark rays refer to the scene.
class DatasetPlan {
 public:
  // InputError for a bad spec or scene, a pose or camera the engine refuses, or a bad shard.
  // The plan reads `spec` for as long as it lives: a temporary spec does not compile.
  DatasetPlan(const DatasetSpec& spec, const DatasetRunOptions& options);
  DatasetPlan(DatasetSpec&& spec, const DatasetRunOptions& options) = delete;
  DatasetPlan(const DatasetPlan&) = delete;
  DatasetPlan& operator=(const DatasetPlan&) = delete;

  const DatasetSpec& spec() const { return spec_; }
  const Scene& scene() const { return scene_; }
  const std::vector<CameraSetup>& setups() const { return setups_; }
  // Every frame's robot pose (the whole dataset's), at its exposure start, and its velocity over
  // its exposure.
  const std::vector<RobotPose>& poses() const { return poses_; }
  const std::vector<BodyVelocity>& velocities() const { return velocities_; }
  Engine& engine() const { return *engine_; }
  const FrameRange& range() const { return range_; }
  const FrameOutputPlan& outputs() const { return outputs_; }
  const IdTables& ids() const { return ids_; }
  const nlohmann::json& header() const { return header_; }        // the manifest's (docs/dataset-format.md)
  const std::vector<StaticFile>& statics() const { return statics_; }  // every camera's
  // Relative to the dataset folder, made before frames are written.
  const std::vector<std::string>& folders() const { return folders_; }
  const std::vector<std::string>& notes() const { return notes_; }  // for the user: outputs the engine does not write
  const RayScene* rays() const { return rays_.get(); }           // for landmark annotations, when the outputs have any
  const RenderRequest& request() const { return request_; }       // the spec's, with the run's threads
  const std::optional<CalibrationSequence>& calibration() const { return calibration_; }
  bool movesTarget() const { return calibration_.has_value(); }

  // Frame `frame`'s scene, with its engine and its rays when asked: the target where the frame
  // holds it. Only for a plan that movesTarget().
  std::unique_ptr<FrameWorld> frameWorld(int frame, bool withEngine, bool withRays) const;
  // What one frame holds while it is rendered and encoded: every camera's frame, AOVs, files and
  // sample table (FastRenderer::frameBytes; docs/robustness.md, "Memory"), and a calibration
  // sequence's own world of the frame (frameWorldBytes). The scheduler renders
  // as many frames at once as memory holds.
  int64_t frameBytes() const;
  // Camera `camera`'s rig during frame `frame`: its setup's, shaken by the spec's vibration.
  RigSpec frameRig(int frame, size_t camera) const;
  // The robot's tilt during frame `frame`: the spec's, rocked by its vibration.
  RobotTilt robotTilt(int frame) const;
  // Camera `camera`'s placement during frame `frame` (placement.h): the robot's pose and
  // velocity, the camera's mount, the robot's tilt.
  CameraPlacement placement(int frame, size_t camera) const;
  // Whether frames shake each camera's rig (the manifest then records every frame's rig).
  bool vibrates() const { return spec_.vibration.shakesRigs(); }
  // Whether frames differ in more than their pose (a shaken rig, a velocity), so that an engine
  // rendering many poses with one setting (Blender's batches) must take them one at a time.
  bool framesHaveOwnSettings() const {
    return vibrates() || movesTarget() || std::any_of(velocities_.begin(), velocities_.end(), [](const BodyVelocity& v) { return !v.still(); });
  }

 private:
  // The calibration sequence's parts of the plan (dataset_plan_calibration.cpp): its target and
  // board poses, with the robot at its one pose in every frame; then every camera's files.
  void startCalibrationSequence();
  void addCalibrationFiles();

  const DatasetSpec& spec_;
  Scene scene_;
  std::vector<CameraSetup> setups_;
  std::vector<RobotPose> poses_;
  std::vector<BodyVelocity> velocities_;
  std::unique_ptr<Engine> engine_;
  FrameRange range_;
  FrameOutputPlan outputs_;
  IdTables ids_;
  nlohmann::json header_;
  std::vector<StaticFile> statics_;
  std::vector<std::string> folders_;
  std::vector<std::string> notes_;
  std::unique_ptr<RayScene> rays_;
  RenderRequest request_;
  std::optional<CalibrationSequence> calibration_;
};

// The memory of one frame's own world (DatasetPlan::frameWorld) over `scene`: its copy (textures
// shared) and `rayScenes` Embree scenes built over it. Counted in frameBytes, so that the frames
// rendered at once fit (docs/robustness.md, "Memory").
int64_t frameWorldBytes(const Scene& scene, int rayScenes);

}  // namespace omnicam
