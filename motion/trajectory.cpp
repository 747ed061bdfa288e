#include "trajectory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace omnicam {

Trajectory::Trajectory(std::vector<RobotPose> waypoints, std::vector<double> times)
    : waypoints_(std::move(waypoints)), times_(std::move(times)) {
  for (size_t k = 0; k + 1 < waypoints_.size(); ++k)
    velocities_.push_back(velocityBetween(waypoints_[k], waypoints_[k + 1], times_[k + 1] - times_[k]));
}

Trajectory Trajectory::atSpeed(const std::vector<RobotPose>& waypoints, double speed, double yawRateDegPerS) {
  if (waypoints.empty()) throw std::invalid_argument("trajectory: needs at least one waypoint");
  std::vector<RobotPose> kept{waypoints.front()};
  std::vector<double> times{0.0};
  for (size_t k = 1; k < waypoints.size(); ++k) {
    // The arc's length and turn: the velocity that drives the segment in one second.
    const BodyVelocity unit = velocityBetween(kept.back(), waypoints[k], 1.0);
    const double seconds = std::max(std::hypot(unit.vx, unit.vy) / speed, std::abs(unit.yawRateDegPerS) / yawRateDegPerS);
    if (seconds == 0.0) continue;
    kept.push_back(waypoints[k]);
    times.push_back(times.back() + seconds);
  }
  return Trajectory(std::move(kept), std::move(times));
}

size_t Trajectory::segmentAt(double seconds) const {
  // The last segment starting at or before `seconds`.
  const auto after = std::upper_bound(times_.begin(), times_.end() - 1, seconds);
  return static_cast<size_t>(std::max<std::ptrdiff_t>(0, after - times_.begin() - 1));
}

RobotPose Trajectory::poseAt(double seconds) const {
  if (velocities_.empty() || seconds <= start()) return waypoints_.front();
  if (seconds >= end()) return waypoints_.back();
  const size_t k = segmentAt(seconds);
  return poseAfter(waypoints_[k], velocities_[k], seconds - times_[k]);
}

BodyVelocity Trajectory::velocityAt(double seconds) const {
  if (velocities_.empty()) return {};
  return velocities_[std::min(segmentAt(seconds), velocities_.size() - 1)];
}

}  // namespace omnicam
