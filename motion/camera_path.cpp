#include "camera_path.h"

#include <cmath>

namespace omnicam {

std::vector<RobotPose> sampleWaypointPath(const std::vector<Vec2>& waypoints, int frames) {
  std::vector<double> cumulative{0.0};
  for (size_t i = 1; i < waypoints.size(); ++i)
    cumulative.push_back(cumulative.back() + (waypoints[i] - waypoints[i - 1]).norm());
  const double total = cumulative.back();
  std::vector<RobotPose> poses;
  size_t segment = 0;
  for (int f = 0; f < frames; ++f) {
    const double s = frames == 1 ? 0.0 : total * f / (frames - 1);
    while (segment + 2 < waypoints.size() && s >= cumulative[segment + 1]) ++segment;
    const Vec2 a = waypoints[segment], b = waypoints[segment + 1];
    const double length = cumulative[segment + 1] - cumulative[segment];
    const double t = length > 0.0 ? std::min(1.0, (s - cumulative[segment]) / length) : 0.0;
    const Vec2 p = a + t * (b - a);
    poses.push_back({p.x(), p.y(), degrees(std::atan2(b.y() - a.y(), b.x() - a.x()))});
  }
  return poses;
}

}  // namespace omnicam
