#include "landmark_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace omnicam {

std::optional<RangeBearing> rangeBearingFromRaster(const RigSpec& rig, const Vec2& raster, double pointHeight) {
  const OmniCamera camera = rig.camera();
  // viewpointFromCamera: the robot's axes (x forward, y left, z up) at F'.
  const Vec3 direction = unifiedCameraFromViewpoint().inverse().linear() * camera.cameraFromRaster(raster);
  const double rise = pointHeight - rig.height;  // from F' to the point's height
  if (std::abs(direction.z()) < 1e-12 || rise / direction.z() <= 0.0) return std::nullopt;
  const double t = rise / direction.z();
  return RangeBearing(t * std::hypot(direction.x(), direction.y()), std::atan2(direction.y(), direction.x()));
}

Interval distanceBetweenSightings(const Interval& a, double bearingA, const Interval& b, double bearingB) {
  const double c = std::cos(bearingA - bearingB);
  auto distance = [c](double ra, double rb) {
    if (std::isinf(ra) || std::isinf(rb)) return std::numeric_limits<double>::infinity();
    return std::sqrt(std::max(0.0, ra * ra + rb * rb - 2.0 * ra * rb * c));
  };
  // |ra·u_a − rb·u_b| is convex in (ra, rb) and least where ra·u_a = rb·u_b, a set that crosses the
  // box's edges if it enters the box; so the least value is on an edge, where the other range is
  // best clamped to its interval, and the greatest at a corner.
  Interval d{std::numeric_limits<double>::infinity(), 0.0};
  for (const double ra : {a.lo, a.hi}) d.lo = std::min(d.lo, distance(ra, std::clamp(ra * c, b.lo, b.hi)));
  for (const double rb : {b.lo, b.hi}) d.lo = std::min(d.lo, distance(std::clamp(rb * c, a.lo, a.hi), rb));
  for (const double ra : {a.lo, a.hi})
    for (const double rb : {b.lo, b.hi}) d.hi = std::max(d.hi, distance(ra, rb));
  return d;
}

RangeBearing predictedSighting(const Vec2& a, const RangeBearing& seenA, const Vec2& b, const RangeBearing& seenB,
                               const Vec2& c) {
  // The sightings in the robot's frame (x forward, y left).
  const Vec2 robotA = seenA(0) * Vec2(std::cos(seenA(1)), std::sin(seenA(1)));
  const Vec2 robotB = seenB(0) * Vec2(std::cos(seenB(1)), std::sin(seenB(1)));
  const Vec2 chordMap = b - a, chordRobot = robotB - robotA;
  const double yaw = std::atan2(chordMap.y(), chordMap.x()) - std::atan2(chordRobot.y(), chordRobot.x());
  const Eigen::Rotation2Dd worldFromRobot(yaw);
  const Vec2 robotPosition = 0.5 * (a + b) - worldFromRobot * (0.5 * (robotA + robotB));
  const Vec2 robotC = worldFromRobot.inverse() * (c - robotPosition);
  return RangeBearing(robotC.norm(), std::atan2(robotC.y(), robotC.x()));
}

bool sightingsAgree(const Sighting& a, const Sighting& b, double slack) {
  const Interval d = distanceBetweenSightings(a.range, a.bearing, b.range, b.bearing);
  const double mapDistance = (a.landmark - b.landmark).norm();
  return mapDistance >= d.lo - slack && mapDistance <= d.hi + slack;
}

bool sightingsAgree(const Sighting& a, const Sighting& b, const Sighting& c, double slack) {
  auto rangeAt = [](const Interval& r, int k) {
    return r.lo * std::pow(std::min(r.hi, kFarthestSightingM) / r.lo, k / static_cast<double>(kTripleGridSteps));
  };
  for (int ka = 0; ka <= kTripleGridSteps; ++ka)
    for (int kb = 0; kb <= kTripleGridSteps; ++kb) {
      const RangeBearing predicted = predictedSighting(a.landmark, RangeBearing(rangeAt(a.range, ka), a.bearing),
                                                       b.landmark, RangeBearing(rangeAt(b.range, kb), b.bearing), c.landmark);
      const double bearingSlack = std::atan2(slack, std::max(predicted(0), slack));
      if (std::abs(wrapAngle(predicted(1) - c.bearing)) <= bearingSlack && predicted(0) - slack <= c.range.hi &&
          predicted(0) + slack >= c.range.lo)
        return true;
    }
  return false;
}

}  // namespace omnicam
