#pragma once
// The robot on the floor: the first link of the frame chain (placement.h composes the chain).
//   robot: origin on the floor below F', x forward, y left, z up (yaw CCW from world +X).
#include "geometry.h"

namespace omnicam {

struct RobotPose {
  double x = 0.0, y = 0.0, yawDeg = 0.0;
};

Rigid worldFromRobot(const RobotPose& pose);

}  // namespace omnicam
