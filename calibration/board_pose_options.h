#pragma once
// How board poses are drawn (board_poses.h): apart, so that a dataset spec's reader can hold them
// without knowing cameras or renderers.
#include <cstdint>
#include <optional>

namespace omnicam {

struct BoardPoseOptions {
  int count = 20;                 // poses kept
  double nearM = 0.3, farM = 1.0;  // the board's centre from the viewpoint (metres)
  double maxTiltDeg = 40.0;       // away from facing the camera
  int minSeenCorners = 12;        // a pose with fewer corners seen is drawn again
  uint64_t seed = 1;
  int maxDraws = 100000;          // gives up (InputError) after this many draws
  // A floor the board cannot go through: every corner of the pattern at least 1 cm above this
  // height (metres, in the frame the poses are given in); none: anywhere.
  std::optional<double> floorZ;
};

}  // namespace omnicam
