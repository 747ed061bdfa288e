// Projecting a point and inverting its pixel at the point's known height gives back its range
// and bearing (closed form: the horizontal distance and angle from F').
#include "landmark_geometry.h"
#include "placement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace omnicam {
namespace {

void expectInversionRecoversRangeAndBearing(const RigSpec& rig) {
  const RobotPose pose{0.3, -0.4, 35.0};
  const OmniCamera camera = rig.camera();
  for (const Vec3& point : {Vec3(1.35, -1.95, 0.35), Vec3(-1.35, 1.95, 0.25), Vec3(2.0, 0.5, 0.0), Vec3(0.0, 0.4, 0.1)}) {
    // The projection through the placement's whole frame chain (world ← robot ← viewpoint ← camera).
    const auto raster = camera.rasterFromCamera(CameraPlacement(pose).worldFromCamera(rig).inverse() * point);
    ASSERT_TRUE(raster);
    const auto rb = rangeBearingFromRaster(rig, *raster, point.z());
    ASSERT_TRUE(rb);
    const double dx = point.x() - pose.x, dy = point.y() - pose.y;
    EXPECT_NEAR(rb->x(), std::hypot(dx, dy), 1e-9) << rig.tiltDeg[0] << " " << rig.tiltDeg[1];
    EXPECT_NEAR(wrapAngle(rb->y() - (std::atan2(dy, dx) - radians(pose.yawDeg))), 0.0, 1e-9);
  }
}

TEST(LandmarkGeometry, InvertingTheProjectionAtTheKnownHeightRecoversRangeAndBearing) {
  RigSpec rig;
  expectInversionRecoversRangeAndBearing(rig);
  const OmniCamera camera = rig.camera();
  // A point at the viewpoint's own height lies on the horizon: no finite range.
  EXPECT_FALSE(rangeBearingFromRaster(rig, {180.0 + camera.horizonRadius(), 180.0}, rig.height));
  // Above F' (seen above the horizon), a point cannot be on a ray that goes down.
  EXPECT_FALSE(rangeBearingFromRaster(rig, {190.0, 180.0}, 1.0));
}

// A rig rocked on its mount: F' moves off the robot's vertical axis and the rays turn with it;
// ranges and bearings stay the robot's. Level-rig inversion would be off by centimetres here.
TEST(LandmarkGeometry, ATiltedRigsRangeAndBearingAreTheRobotsNotTheLevelRigs) {
  RigSpec rig;
  rig.tiltDeg = {4.0, -3.0};
  expectInversionRecoversRangeAndBearing(rig);
  // The same pixel read as a level rig's lies elsewhere.
  const RigSpec level;
  const Vec2 raster = *level.camera().rasterFromCamera(CameraPlacement(RobotPose{}).worldFromCamera(level).inverse() *
                                                       Vec3(1.0, 0.5, 0.0));
  const auto tilted = rangeBearingFromRaster(rig, raster, 0.0), levelRead = rangeBearingFromRaster(level, raster, 0.0);
  ASSERT_TRUE(tilted && levelRead);
  EXPECT_GT(std::abs((*tilted)(0) - (*levelRead)(0)), 0.02);
}

TEST(LandmarkGeometry, DistanceBetweenSightingsMatchesClosedFormsAndADenseSearch) {
  // Closed forms: same bearing, d = |r_a − r_b|; perpendicular, d = √(r_a² + r_b²); opposite, r_a + r_b.
  auto expectInterval = [](const Interval& d, double lo, double hi) {
    EXPECT_NEAR(d.lo, lo, 1e-12);
    EXPECT_NEAR(d.hi, hi, 1e-12);
  };
  expectInterval(distanceBetweenSightings({1, 2}, 0.3, {3, 4}, 0.3), 1.0, 3.0);
  expectInterval(distanceBetweenSightings({1, 3}, 0.3, {2, 4}, 0.3), 0.0, 3.0);  // the ranges can coincide
  expectInterval(distanceBetweenSightings({1, 2}, 0.0, {3, 4}, kPi / 2), std::sqrt(10.0), std::sqrt(20.0));
  expectInterval(distanceBetweenSightings({1, 2}, 1.0, {3, 4}, 1.0 + kPi), 4.0, 6.0);
  // A range up to the horizon leaves the distance unbounded above.
  const double inf = std::numeric_limits<double>::infinity();
  const Interval open = distanceBetweenSightings({2, inf}, 0.0, {1, 1.5}, 0.4);
  EXPECT_TRUE(std::isinf(open.hi));
  EXPECT_NEAR(open.lo, std::hypot(2.0 - 1.5 * std::cos(0.4), 1.5 * std::sin(0.4)), 1e-12);
  // Any bearings: against the least and greatest over a dense grid of the two ranges.
  for (const double gap : {0.1, 0.7, 1.6, 2.5, 3.1}) {
    const Interval a{1.2, 2.9}, b{0.4, 3.3};
    const Interval d = distanceBetweenSightings(a, 0.2, b, 0.2 + gap);
    double lo = inf, hi = 0.0;
    for (int i = 0; i <= 400; ++i)
      for (int j = 0; j <= 400; ++j) {
        const double ra = a.lo + (a.hi - a.lo) * i / 400.0, rb = b.lo + (b.hi - b.lo) * j / 400.0;
        const double dd = std::hypot(ra - rb * std::cos(gap), rb * std::sin(gap));
        lo = std::min(lo, dd), hi = std::max(hi, dd);
      }
    EXPECT_NEAR(d.lo, lo, 2e-3) << gap;
    EXPECT_NEAR(d.hi, hi, 1e-12) << gap;
    EXPECT_LE(d.lo, lo + 1e-12) << gap;  // the grid can only overshoot the least
  }
}

TEST(LandmarkGeometry, TwoExactSightingsPredictWhereAThirdLandmarkIsSeen) {
  // Sightings computed forward from a pose (the EKF's measurement model h) give back that pose, so the third landmark is predicted exactly where the pose sees it.
  const Vec2 a(2.7, 1.8), b(-2.7, 1.8), c(-2.7, -1.8), d(2.7, -1.8);
  for (const RobotPose& pose : {RobotPose{0.3, -0.4, 35.0}, RobotPose{-1.9, 1.2, -170.0}, RobotPose{2.0, 0.0, 90.0}}) {
    auto seen = [&](const Vec2& p) { return measurementModel(Vec3(pose.x, pose.y, radians(pose.yawDeg)), p); };
    for (const Vec2& third : {c, d}) {
      const RangeBearing predicted = predictedSighting(a, seen(a), b, seen(b), third);
      EXPECT_NEAR(predicted(0), seen(third)(0), 1e-9);
      EXPECT_NEAR(wrapAngle(predicted(1) - seen(third)(1)), 0.0, 1e-9);
    }
    // A range 10 cm long on both sightings moves the robot and so the prediction.
    const RangeBearing off = predictedSighting(a, seen(a) + RangeBearing(0.1, 0.0), b, seen(b) + RangeBearing(0.1, 0.0), c);
    EXPECT_GT(std::abs(off(0) - seen(c)(0)) + std::abs(wrapAngle(off(1) - seen(c)(1))), 1e-3);
  }
}

TEST(LandmarkGeometry, SightingsFromOnePlaceAgreeAndAMovedOneDoesNot) {
  const Vec2 a(2.7, 1.8), b(-2.7, 1.8), c(-2.7, -1.8);
  const RobotPose pose{0.3, -0.4, 35.0};
  // Exact sightings, each range known to ±2 %.
  auto seen = [&](const Vec2& p, double bearingOffset = 0.0, double rangeScale = 1.0) {
    const RangeBearing exact = measurementModel(Vec3(pose.x, pose.y, radians(pose.yawDeg)), p);
    const double range = rangeScale * exact(0);
    return Sighting{p, {0.98 * range, 1.02 * range}, wrapAngle(exact(1) + bearingOffset)};
  };
  const double slack = 0.2;
  EXPECT_TRUE(sightingsAgree(seen(a), seen(b), slack));
  EXPECT_TRUE(sightingsAgree(seen(a), seen(b), seen(c), slack));
  // c seen 1.3 m too far: its distance to a or b no longer matches the map.
  EXPECT_FALSE(sightingsAgree(seen(a), seen(c, 0.0, 1.3), slack));
  EXPECT_FALSE(sightingsAgree(seen(a), seen(b), seen(c, 0.0, 1.3), slack));
  // c seen near the horizon (range unbounded) 25° off its bearing: the pair a–c still allows it
  // (some range on c's ray lies at the map distance from a), but a and b place the robot, and
  // from there c is not where it is seen.
  const double inf = std::numeric_limits<double>::infinity();
  Sighting far = seen(c, radians(25.0));
  far.range = {1.0, inf};
  EXPECT_TRUE(sightingsAgree(seen(a), far, slack));
  EXPECT_TRUE(sightingsAgree(seen(b), far, slack));
  EXPECT_FALSE(sightingsAgree(seen(a), seen(b), far, slack));
  // On its true bearing, unbounded, it agrees; and with a and b unbounded as well, the grid
  // still finds the ranges that place the robot.
  Sighting farTrue = seen(c);
  farTrue.range = {1.0, inf};
  EXPECT_TRUE(sightingsAgree(seen(a), seen(b), farTrue, slack));
  Sighting aFar = seen(a), bFar = seen(b);
  aFar.range.hi = bFar.range.hi = inf;
  EXPECT_TRUE(sightingsAgree(aFar, bFar, seen(c), slack));
}

}  // namespace
}  // namespace omnicam
