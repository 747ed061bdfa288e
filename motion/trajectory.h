#pragma once
// A robot driving through waypoints in time (docs/motion.md, "Timed paths"): each segment between
// neighbouring waypoints is driven with the one constant body velocity that takes the first to
// the second in the segment's duration (an arc on SE(2), motion.h), so the pose at any instant
// and the velocity held over an exposure are exact. Durations come from timestamps per waypoint,
// or from a speed and a turn rate: each segment takes as long as the slower of driving its arc at
// the speed and turning its angle at the rate.
#include <vector>

#include "motion.h"

namespace omnicam {

class Trajectory {
 public:
  // `times` strictly increasing, one per waypoint (the caller checks; at least one waypoint).
  Trajectory(std::vector<RobotPose> waypoints, std::vector<double> times);
  // Waypoints driven at `speed` m/s and turned at `yawRateDegPerS`, both > 0, from time 0. A
  // waypoint equal to the one before it (no distance, no turn) adds nothing. At least one waypoint
  // (std::invalid_argument).
  static Trajectory atSpeed(const std::vector<RobotPose>& waypoints, double speed, double yawRateDegPerS);

  double start() const { return times_.front(); }
  double end() const { return times_.back(); }
  // The pose at `seconds` (clamped to [start, end]).
  RobotPose poseAt(double seconds) const;
  // The velocity held from `seconds` on: that of the segment it falls in (the last one's at the
  // end; still for a single waypoint).
  BodyVelocity velocityAt(double seconds) const;

 private:
  size_t segmentAt(double seconds) const;
  std::vector<RobotPose> waypoints_;
  std::vector<double> times_;
  std::vector<BodyVelocity> velocities_;  // segment k: waypoint k → k + 1
};

}  // namespace omnicam
