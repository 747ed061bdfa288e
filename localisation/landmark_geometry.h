#pragma once
// Range and bearing of a landmark from where it appears in the omni image (thesis §3.4.1): the
// pixel gives the viewing ray from F'; a landmark band at a known height above the floor meets
// that ray at one point. The thesis inverted its bird's-eye equations (3.3–3.5); this inverts
// the exact model.
#include <optional>

#include "ekf.h"
#include "rig.h"

namespace omnicam {

// Range (metres, horizontal from the robot's origin — the rig's foot, its mount's place on the
// robot not counted — below F' on a level rig) and bearing (radians CCW from the forward axis)
// of the point at height `pointHeight` above the floor seen at continuous raster position
// `raster` (centres at +0.5) by a camera with `rig`, tilted as the rig says (robotFromViewpoint). nullopt when the ray never reaches that height (the point
// would be at or beyond the horizon). InputError for a rig no central model describes.
std::optional<RangeBearing> rangeBearingFromRaster(const RigSpec& rig, const Vec2& raster, double pointHeight);

// Range (horizontal from the frame's vertical axis) and bearing (CCW from its x axis) of the
// point at height `height` on the ray from `origin` along `direction`, in a frame whose z is up;
// nullopt when the ray never reaches that height.
std::optional<RangeBearing> rangeBearingAlong(const Vec3& origin, const Vec3& direction, double height);

// The horizontal distance between two points seen from one place at bearings `bearingA` and
// `bearingB` (radians) with ranges anywhere in [a.lo, a.hi] and [b.lo, b.hi] (hi may be +∞): its
// least and greatest value, d² = r_a² + r_b² − 2 r_a r_b cos(bearingA − bearingB). Two sightings
// of landmarks whose map distance lies outside it cannot both be right, wherever the robot is.
struct Interval {
  double lo = 0.0, hi = 0.0;
};
Interval distanceBetweenSightings(const Interval& a, double bearingA, const Interval& b, double bearingB);

// Where a third landmark at map position `c` is seen from the place that puts landmarks at map
// positions `a` and `b` at sightings `seenA` and `seenB` (range, bearing): the pose turns the
// sightings' chord onto the map's and matches their midpoints (exact when the sightings are).
RangeBearing predictedSighting(const Vec2& a, const RangeBearing& seenA, const Vec2& b, const RangeBearing& seenB,
                               const Vec2& c);

// A landmark at map position `landmark` seen at a range somewhere in `range` and at `bearing`.
struct Sighting {
  Vec2 landmark;
  Interval range;
  double bearing = 0.0;
};

// Whether two sightings can both be right from one place: their map distance within the least
// and greatest distance their ranges and bearings allow, ± slack.
bool sightingsAgree(const Sighting& a, const Sighting& b, double slack);

// Whether three sightings can all be right from one place: some ranges within a's and b's
// intervals that put a and b at their map distance apart (± slack) place the robot where c is
// predicted within `slack` of c's range interval, and within the slack seen from c's predicted
// range of c's bearing. A pair's distance cannot tell this when a range is unbounded (a sighting
// near the horizon); two sightings and their bearings pin the robot down for a third. Two
// sightings at their map distance leave one free parameter: one range, searched on a grid
// geometric in range (a ratio step suits a range known to a pixel), kTripleGridSteps + 1 values
// an interval, an unbounded one taken up to kFarthestSightingM (beyond any arena's landmarks),
// each with the other's ranges that keep the map distance, and then the other way round.
constexpr int kTripleGridSteps = 32;
constexpr double kFarthestSightingM = 50.0;
bool sightingsAgree(const Sighting& a, const Sighting& b, const Sighting& c, double slack);

}  // namespace omnicam
