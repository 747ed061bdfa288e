#include "landmark_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "placement.h"

namespace omnicam {

std::optional<RangeBearing> rangeBearingAlong(const Vec3& origin, const Vec3& direction, double height) {
  if (std::abs(direction.z()) < 1e-12) return std::nullopt;
  const double t = (height - origin.z()) / direction.z();
  if (!(t > 0.0)) return std::nullopt;
  const Vec3 p = origin + t * direction;
  return RangeBearing(std::hypot(p.x(), p.y()), std::atan2(p.y(), p.x()));
}

std::optional<RangeBearing> rangeBearingFromRaster(const RigSpec& rig, const Vec2& raster, double pointHeight) {
  const OmniCamera camera = rig.camera();
  // The ray from F' in the robot's frame: a tilted rig moves F' off the robot's vertical axis.
  const Rigid robotFromCam = robotFromCamera(rig);
  return rangeBearingAlong(robotFromCam.translation(), robotFromCam.linear() * camera.cameraFromRaster(raster), pointHeight);
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
  const Vec2 robotPosition = 0.5 * (a + b) - Eigen::Rotation2Dd(yaw) * (0.5 * (robotA + robotB));
  return measurementModel(Vec3(robotPosition.x(), robotPosition.y(), yaw), c);
}

bool sightingsAgree(const Sighting& a, const Sighting& b, double slack) {
  const Interval d = distanceBetweenSightings(a.range, a.bearing, b.range, b.bearing);
  const double mapDistance = (a.landmark - b.landmark).norm();
  return mapDistance >= d.lo - slack && mapDistance <= d.hi + slack;
}

bool sightingsAgree(const Sighting& a, const Sighting& b, const Sighting& c, double slack) {
  // A range on a geometric grid over the interval (a ratio step suits a range known to a pixel).
  auto rangeAt = [](const Interval& r, int k) {
    const double top = std::max(r.lo, std::min(r.hi, kFarthestSightingM));
    if (r.lo <= 0.0) return top * k / kTripleGridSteps;
    return r.lo * std::pow(top / r.lo, k / static_cast<double>(kTripleGridSteps));
  };
  const double mapDistance = (a.landmark - b.landmark).norm();
  auto placesC = [&](double ra, double rb) {
    const RangeBearing predicted =
        predictedSighting(a.landmark, RangeBearing(ra, a.bearing), b.landmark, RangeBearing(rb, b.bearing), c.landmark);
    const double bearingSlack = std::atan2(slack, std::max(predicted(0), slack));
    return std::abs(wrapAngle(predicted(1) - c.bearing)) <= bearingSlack && predicted(0) - slack <= c.range.hi &&
           predicted(0) + slack >= c.range.lo;
  };
  // Each grid range of `s`, and the ranges of `t` that put the two at their map distance
  // (|r_s·u_s − r_t·u_t| = D: r_t = r_s cos Δ ± √(D² − r_s² sin² Δ)), within t's interval ± slack.
  auto along = [&](const Sighting& s, const Sighting& t, bool sIsA) {
    const double cosGap = std::cos(s.bearing - t.bearing), sinGap = std::sin(s.bearing - t.bearing);
    for (int k = 0; k <= kTripleGridSteps; ++k) {
      const double rs = rangeAt(s.range, k);
      const double reach = mapDistance * mapDistance - rs * rs * sinGap * sinGap;
      // Too far off t's ray for the map distance: its nearest point, if within slack of it.
      const double root = reach >= 0.0 ? std::sqrt(reach) : (rs * std::abs(sinGap) <= mapDistance + slack ? 0.0 : -1.0);
      if (root < 0.0) continue;
      for (const double rt : {rs * cosGap - root, rs * cosGap + root}) {
        if (rt <= 0.0 || rt < t.range.lo - slack || rt > t.range.hi + slack) continue;
        const double kept = std::clamp(rt, t.range.lo, t.range.hi);
        if (sIsA ? placesC(rs, kept) : placesC(kept, rs)) return true;
      }
    }
    return false;
  };
  return along(a, b, true) || along(b, a, false);
}

}  // namespace omnicam
