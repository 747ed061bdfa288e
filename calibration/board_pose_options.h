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
  // height (metres, z in the world frame of boardPoses' worldFromViewpoint); none: anywhere.
  std::optional<double> floorZ;
  // What must clear that floor: the printed board's outline with this white margin (metres;
  // targetBoardOutline), the whole board a dataset renders; none: the pattern's corners, as the
  // calibration study measured its boards.
  std::optional<double> boardMarginM;
  // Every point of that board at least this far from the viewpoint (a dataset's sequence: nearer,
  // a board reaches into the mirror); none: only its centre's distance (nearM) counts, as the study drew.
  std::optional<double> minBoardDistanceM;
};

}  // namespace omnicam
