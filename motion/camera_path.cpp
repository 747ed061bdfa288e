#include "camera_path.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace omnicam {

std::vector<RobotPose> sampleWaypointPath(const std::vector<Vec2>& waypoints, int frames) {
  if (waypoints.size() < 2) throw std::invalid_argument("waypoint path: needs at least two waypoints");
  std::vector<double> cumulative{0.0};
  for (size_t i = 1; i < waypoints.size(); ++i)
    cumulative.push_back(cumulative.back() + (waypoints[i] - waypoints[i - 1]).norm());
  const double total = cumulative.back();
  // Each segment's heading; a segment of no length (a waypoint repeated) keeps the one before it
  // (at the start, the first one after it): atan2(0, 0) would turn the robot to 0°.
  std::vector<std::optional<double>> ownHeadingDeg(waypoints.size() - 1);
  for (size_t k = 0; k < ownHeadingDeg.size(); ++k)
    if (const Vec2 d = waypoints[k + 1] - waypoints[k]; d.x() != 0.0 || d.y() != 0.0)
      ownHeadingDeg[k] = degrees(std::atan2(d.y(), d.x()));
  const auto firstHeading = std::find_if(ownHeadingDeg.begin(), ownHeadingDeg.end(), [](const auto& h) { return h.has_value(); });
  double carried = firstHeading == ownHeadingDeg.end() ? 0.0 : **firstHeading;
  std::vector<double> headingDeg;
  for (const std::optional<double>& own : ownHeadingDeg) headingDeg.push_back(carried = own.value_or(carried));
  std::vector<RobotPose> poses;
  size_t segment = 0;
  for (int f = 0; f < frames; ++f) {
    const double s = frames == 1 ? 0.0 : total * f / (frames - 1);
    while (segment + 2 < waypoints.size() && s >= cumulative[segment + 1]) ++segment;
    const Vec2 a = waypoints[segment], b = waypoints[segment + 1];
    const double length = cumulative[segment + 1] - cumulative[segment];
    const double t = length > 0.0 ? std::min(1.0, (s - cumulative[segment]) / length) : 0.0;
    const Vec2 p = a + t * (b - a);
    poses.push_back({p.x(), p.y(), headingDeg[segment]});
  }
  return poses;
}

}  // namespace omnicam
