#pragma once
// The robot's motion while a shutter is open (docs/motion.md): a constant body velocity held from
// the pose at the exposure start, integrated exactly on SE(2), so the robot drives an arc (a line
// when it does not turn). Frame i's pose is the pose at its timestamp, the exposure start.
#include "robot_pose.h"

namespace omnicam {

struct BodyVelocity {
  double vx = 0.0, vy = 0.0;    // m/s in the robot frame: x forward, y left
  double yawRateDegPerS = 0.0;  // counter-clockwise
  bool still() const { return vx == 0.0 && vy == 0.0 && yawRateDegPerS == 0.0; }
  bool operator==(const BodyVelocity&) const = default;
};

// The pose `seconds` after `start` with `velocity` held: start ∘ exp(seconds · twist).
RobotPose poseAfter(const RobotPose& start, const BodyVelocity& velocity, double seconds);

// The body velocity that takes `from` to `to` in `seconds` on SE(2) (the inverse of poseAfter,
// turning by the shorter way round): what a path's neighbouring poses imply.
BodyVelocity velocityBetween(const RobotPose& from, const RobotPose& to, double seconds);

}  // namespace omnicam
