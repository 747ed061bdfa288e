#pragma once
// What a dataset spec asks of a calibration sequence (calibration_sequence.h): apart, so that the
// spec's reader (and its fuzzer) holds it without cameras or renderers.
#include <optional>
#include <string>
#include <vector>

#include "board_pose_options.h"
#include "geometry.h"

namespace omnicam {

namespace limits {
inline constexpr int kMaxCalibrationPoses = 10000;
// A board's distance from the camera (metres), listed or drawn: nearer than 5 cm it would reach
// into the mirror.
inline constexpr double kMinBoardDistanceM = 0.05, kMaxBoardDistanceM = 100.0;
}

// The board's poses, in the first camera's viewpoint frame: drawn (board_poses.h) or listed.
struct CalibrationSequenceSpec {
  std::string target;  // a calibration_target of the scene
  std::optional<BoardPoseOptions> random;
  std::vector<Rigid> listed;  // viewpointFromTarget, one per frame
  bool rosbag = false;        // the images also in a ROS 1 bag (rosbag_file.h)
};

}  // namespace omnicam
