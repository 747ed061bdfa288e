#pragma once
// Poses of a calibration target around the camera, as a person waving a board would hold it: its
// centre at a seeded random distance along a seeded random ray the camera images, its printed
// face turned back toward the camera, then tilted and rolled. Only poses with enough corners seen
// are kept.
#include <cstdint>
#include <optional>
#include <vector>

#include "calibration_target.h"
#include "camera.h"

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

// `count` poses (worldFromTarget for a camera at worldFromViewpoint), each with at least
// minSeenCorners corners seen (imaged inside the rim and the image, on the printed face; no
// occluders: the board alone).
std::vector<Rigid> boardPoses(const Camera& camera, const Rigid& worldFromViewpoint, const TargetPattern& pattern,
                              const BoardPoseOptions& options);

}  // namespace omnicam
