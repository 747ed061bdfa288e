#pragma once
// A calibration sequence (docs/calibration.md, "Calibration sequences"): a scene's calibration
// target held in front of a still robot's camera at one pose per frame, as a person waving a
// board would, and what each frame shows of it: every corner's exact raster point through the
// camera's own project() with why a hidden one is hidden. `omnicam dataset` renders the frames and
// writes these files beside them.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "board_poses.h"
#include "imaged_corners.h"
#include "scene.h"

namespace omnicam {

namespace limits {
inline constexpr int kMaxCalibrationPoses = 10000;
}

// The board's poses, in the first camera's viewpoint frame: drawn (board_poses.h) or listed.
struct CalibrationSequenceSpec {
  std::string target;  // a calibration_target of the scene
  std::optional<BoardPoseOptions> random;
  std::vector<Rigid> listed;  // viewpointFromTarget, one per frame
  bool rosbag = false;        // the images also in a ROS 1 bag (rosbag_file.h)
};

// Index of the scene's calibration target named `name`; -1 when there is none.
int findCalibrationTarget(const Scene& scene, const std::string& name);

// Moves calibration target `target` and its board (a quad of scene.objects) to worldFromTarget.
void placeCalibrationTarget(Scene& scene, int target, const Rigid& worldFromTarget);

// The board's pose of every frame in the viewpoint frame of `camera` (the first camera of the
// robot): the listed ones, or `random->count` drawn ones. InputError when too few can be drawn.
std::vector<Rigid> sequenceBoardPoses(const CalibrationSequenceSpec& spec, const Camera& camera, const TargetPattern& pattern);

// One frame of one camera in <camera>/calibration/corners.json.
nlohmann::json cornersFrameJson(int frame, const Rigid& viewpointFromTarget, const std::vector<ImagedCorner>& corners);

}  // namespace omnicam
