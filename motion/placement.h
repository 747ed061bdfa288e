#pragma once
// A camera placed in the world at every instant of its exposure (docs/motion.md, "The frame
// chain"). This is the one place that composes
//
//   world ← robot(t) ← robot tilt ← mount ← rig tilt ← viewpoint
//
//   robot(t)    the robot's pose t seconds after the exposure start, driven at a constant body
//               velocity (motion.h); still when the velocity is zero
//   robot tilt  the robot rocking on its wheels: every camera it carries tilts alike, about the
//               robot's origin on the floor (roll about x, then pitch about the rolled y)
//   mount       where the camera stands on the robot: its foot's offset from the robot's centre
//               and its turn (a multi-camera robot; zero for one camera)
//   rig tilt    the rig tilted on its own mount, about its foot (RigSpec::tiltDeg), then up to
//               F' at the rig's height: robotFromViewpoint below
//
//   camera      the rig's camera frame: cameraFromViewpoint (rig.h)
//
// Engines, annotations, projection, exporters and Python all ask a placement where the camera
// is; none composes these transforms itself.
#include <array>

#include "geometry.h"
#include "motion.h"
#include "rig.h"

namespace omnicam {

// Where a camera stands on its robot: its foot's offset (m, robot axes) and its turn about z.
struct RobotMount {
  double x = 0.0, y = 0.0, yawDeg = 0.0;
  bool operator==(const RobotMount&) const = default;
};

// The robot's own tilt (degrees): roll about its x axis, then pitch about the rolled y axis.
using RobotTilt = std::array<double, 2>;

// The rig-tilt link: the rig tilted on its mount about its foot, then up to F' at its height.
Rigid robotFromViewpoint(const RigSpec& rig);
// robot ← viewpoint ← camera: where the rig's camera frame (cameraFromViewpoint) sits on the robot.
Rigid robotFromCamera(const RigSpec& rig);

class CameraPlacement {
 public:
  CameraPlacement() : CameraPlacement(RobotPose{}) {}
  // One camera at the centre of a still, level robot: the placement of a single-camera render.
  CameraPlacement(const RobotPose& robot)  // NOLINT: implicit, a pose is the common placement
      : CameraPlacement(robot, BodyVelocity{}) {}
  CameraPlacement(const RobotPose& robot, const BodyVelocity& velocity, const RobotMount& mount = {},
                  const RobotTilt& robotTiltDeg = {0.0, 0.0});

  const RobotPose& robot() const { return robot_; }  // at the exposure start
  const BodyVelocity& velocity() const { return velocity_; }
  const RobotMount& mount() const { return mount_; }
  const RobotTilt& robotTiltDeg() const { return robotTiltDeg_; }
  bool still() const { return velocity_.still(); }

  // The camera's foot: the mount's point on the floor and its heading, `seconds` after the
  // exposure start (the robot level). Bearings are measured from this heading.
  RobotPose footAt(double seconds) const;
  // The chain above, `seconds` after the exposure start.
  Rigid worldFromViewpoint(const RigSpec& rig, double seconds = 0.0) const;
  // The same in the rig's camera axes (rig.h's cameraFromViewpoint).
  Rigid worldFromCamera(const RigSpec& rig, double seconds = 0.0) const;
  // This camera on a still robot where this one is `seconds` after its start: one instant of a
  // moving frame, for engines that render still instants. Gives exactly the same transforms.
  CameraPlacement frozenAt(double seconds) const;
  // The same camera in a world moved by (dx, dy): every transform's translation moved alike.
  CameraPlacement translated(double dx, double dy) const;

 private:
  RobotPose robot_;
  BodyVelocity velocity_;
  RobotMount mount_;
  RobotTilt robotTiltDeg_{0.0, 0.0};
  // The chain worked out once: the foot's own motion on SE(2) (robot ∘ mount, exactly), and the
  // robot's tilt seen from the foot (the identity on a level robot).
  RobotPose footStart_;
  BodyVelocity footVelocity_;
  Rigid footFromTiltedFoot_ = Rigid::Identity();
};

// True when a frame's samples see the camera in more than one place: the robot moves while a
// shutter that is not an instant is open.
bool moving(const CameraPlacement& placement, const RigSpec& rig);
// InputError("<what>: ...") if the robot moves but the rig's shutter is an instant: the frame
// would be the still one, and a velocity that changes nothing is refused, not ignored.
void checkMotionIsSeen(const CameraPlacement& placement, const RigSpec& rig, const std::string& what);

}  // namespace omnicam
