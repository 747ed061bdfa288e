#pragma once
#include <vector>

#include "geometry.h"
#include "robot_pose.h"

namespace omnicam {

// `frames` poses spaced evenly by arc length along a polyline of (x, y) waypoints, from the
// first waypoint to the last, each heading along its segment (at a corner: the outgoing one). At
// least two waypoints (std::invalid_argument).
std::vector<RobotPose> sampleWaypointPath(const std::vector<Vec2>& waypoints, int frames);

}  // namespace omnicam
