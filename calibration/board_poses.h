#pragma once
// Poses of a calibration target around the camera, as a person waving a board would hold it: its
// centre at a seeded random distance along a seeded random ray the camera images, its printed
// face turned back toward the camera, then tilted and rolled. Only poses with enough corners seen
// are kept.
#include <vector>

#include "board_pose_options.h"
#include "calibration_target.h"
#include "camera.h"

namespace omnicam {

// A board clears the floor when every one of `points` (target frame: its outline, or its
// pattern's corners) is this far above it.
inline constexpr double kBoardFloorClearanceM = 0.01;
bool boardClearsFloor(const Rigid& worldFromTarget, const std::vector<Vec3>& points, double floorZ);
// The points that must clear the floor by the options (BoardPoseOptions::boardMarginM).
std::vector<Vec3> floorTestPoints(const TargetPattern& pattern, const std::optional<double>& boardMarginM);
// The distance from `point` (world frame) to the nearest point of the flat board whose extent in
// its own plane (z = 0) is the box of `outline` (target frame; floorTestPoints' points).
double boardDistance(const Rigid& worldFromTarget, const std::vector<Vec3>& outline, const Vec3& point);

// `count` poses (worldFromTarget for a camera at worldFromViewpoint), each with at least
// minSeenCorners corners seen (imaged inside the rim and the image, on the printed face; no
// occluders: the board alone) and, with options.floorZ, clearing that floor (boardClearsFloor).
std::vector<Rigid> boardPoses(const Camera& camera, const Rigid& worldFromViewpoint, const TargetPattern& pattern,
                              const BoardPoseOptions& options);

}  // namespace omnicam
