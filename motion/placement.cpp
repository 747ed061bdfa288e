#include "placement.h"

#include "errors.h"

#include <cmath>

namespace omnicam {

namespace {

// The foot's pose: robot ∘ mount on SE(2).
RobotPose footPose(const RobotPose& robot, const RobotMount& mount) {
  const double yaw = radians(robot.yawDeg);
  return {robot.x + std::cos(yaw) * mount.x - std::sin(yaw) * mount.y,
          robot.y + std::sin(yaw) * mount.x + std::cos(yaw) * mount.y, robot.yawDeg + mount.yawDeg};
}

// The foot's body velocity on a robot moving with `robot`: the same turn rate, and ω × offset
// added to the robot's own, seen in the mount's axes. Integrating it from the foot's start gives
// exactly robot(t) ∘ mount.
BodyVelocity footVelocity(const BodyVelocity& robot, const RobotMount& mount) {
  const double omega = radians(robot.yawRateDegPerS);
  const double vx = robot.vx - omega * mount.y, vy = robot.vy + omega * mount.x;
  const double yaw = radians(mount.yawDeg), c = std::cos(yaw), s = std::sin(yaw);
  return {c * vx + s * vy, -s * vx + c * vy, robot.yawRateDegPerS};
}

// A mount places the camera's foot on the robot as a pose places the robot on the floor.
Rigid robotFromFoot(const RobotMount& mount) { return worldFromRobot({mount.x, mount.y, mount.yawDeg}); }

Rigid tiltRotation(const RobotTilt& tiltDeg) {
  Rigid t = Rigid::Identity();
  t.rotate(Eigen::AngleAxisd(radians(tiltDeg[0]), Vec3::UnitX()));
  t.rotate(Eigen::AngleAxisd(radians(tiltDeg[1]), Vec3::UnitY()));
  return t;
}

}  // namespace

Rigid robotFromViewpoint(const RigSpec& rig) {
  Rigid t = tiltRotation(rig.tiltDeg);
  t.translate(Vec3(0.0, 0.0, rig.height));
  return t;
}

CameraPlacement::CameraPlacement(const RobotPose& robot, const BodyVelocity& velocity, const RobotMount& mount,
                                 const RobotTilt& robotTiltDeg)
    : robot_(robot),
      velocity_(velocity),
      mount_(mount),
      robotTiltDeg_(robotTiltDeg),
      footStart_(footPose(robot, mount)),
      footVelocity_(footVelocity(velocity, mount)) {
  // A level robot keeps the exact identity, so a level chain is the product it always was.
  if (robotTiltDeg[0] != 0.0 || robotTiltDeg[1] != 0.0) {
    const Rigid fromFoot = robotFromFoot(mount);
    footFromTiltedFoot_ = fromFoot.inverse() * tiltRotation(robotTiltDeg) * fromFoot;
  }
}

RobotPose CameraPlacement::footAt(double seconds) const { return poseAfter(footStart_, footVelocity_, seconds); }

Rigid CameraPlacement::worldFromViewpoint(const RigSpec& rig, double seconds) const {
  return worldFromRobot(footAt(seconds)) * footFromTiltedFoot_ * robotFromViewpoint(rig);
}

Rigid robotFromCamera(const RigSpec& rig) { return robotFromViewpoint(rig) * cameraFromViewpoint(rig).inverse(); }

Rigid CameraPlacement::worldFromCamera(const RigSpec& rig, double seconds) const {
  return worldFromViewpoint(rig, seconds) * cameraFromViewpoint(rig).inverse();
}

CameraPlacement CameraPlacement::frozenAt(double seconds) const {
  CameraPlacement frozen = *this;
  frozen.robot_ = poseAfter(robot_, velocity_, seconds);
  frozen.velocity_ = {};
  frozen.footStart_ = footAt(seconds);
  frozen.footVelocity_ = {};
  return frozen;
}

CameraPlacement CameraPlacement::translated(double dx, double dy) const {
  CameraPlacement moved = *this;
  moved.robot_.x += dx;
  moved.robot_.y += dy;
  moved.footStart_.x += dx;
  moved.footStart_.y += dy;
  return moved;
}

bool moving(const CameraPlacement& placement, const RigSpec& rig) {
  return !placement.still() && !rig.shutter.instantaneous();
}

void checkMotionIsSeen(const CameraPlacement& placement, const RigSpec& rig, const std::string& what) {
  if (!placement.still() && rig.shutter.instantaneous())
    throw InputError(what + ": the rig's shutter is an instant (no rig.shutter with an exposure_s or a rolling readout), so "
                            "a moving robot renders as a still one: give the rig a shutter (docs/motion.md) or leave " + what + " out");
}

}  // namespace omnicam
