#pragma once
// The camera rig on the robot and the frame chain world ← robot ← viewpoint ← camera.
//   robot:     origin on the floor below F', x forward, y left, z up (yaw CCW from world +X).
//   viewpoint: origin at F' = robot origin + (0, 0, height), robot axes.
//   camera:    unified-model frame at F' (see omni_camera.h).
#include "geometry.h"
#include "omni_camera.h"

namespace omnicam {

struct RobotPose {
  double x = 0.0, y = 0.0, yawDeg = 0.0;
};

struct RigSpec {
  double height = 0.40;            // F' above the floor, metres
  double k = 11.546;               // Baker–Nayar mirror parameter, > 2
  double c = 0.02321;              // focal distance between F and F', metres
  double rimElevationDeg = 45.0;   // mirror rim, degrees above the horizon
  int imageSize = 360;             // square image, pixels
  double framingElevationDeg = 45.0;  // direction that touches the image border

  HyperbolicMirror mirror() const { return {k, c}; }
  OmniCamera camera() const {
    return {mirror(), imageSize, imageSize, rimElevationDeg, framingElevationDeg};
  }
};

Rigid worldFromRobot(const RobotPose& pose);
Rigid robotFromViewpoint(const RigSpec& rig);
// Fixed axis change viewpoint → camera: X = x, Y = −y, Z = −z (a proper rotation).
Rigid cameraFromViewpoint();
Rigid cameraFromWorld(const RigSpec& rig, const RobotPose& pose);
Rigid worldFromCamera(const RigSpec& rig, const RobotPose& pose);

}  // namespace omnicam
