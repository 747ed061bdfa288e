#include "motion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "shutter.h"

namespace omnicam {
namespace {

void expectPose(const RobotPose& got, double x, double y, double yawDeg, double tolerance = 1e-12) {
  EXPECT_NEAR(got.x, x, tolerance);
  EXPECT_NEAR(got.y, y, tolerance);
  EXPECT_NEAR(got.yawDeg, yawDeg, tolerance);
}

TEST(Motion, DrivingStraightMovesAlongTheHeading) {
  expectPose(poseAfter({1.0, 2.0, 30.0}, {2.0, 0.0, 0.0}, 0.5), 1.0 + std::cos(kPi / 6), 2.0 + std::sin(kPi / 6), 30.0);
  // Sideways (y is left): at yaw 90° the robot's left is world −x.
  expectPose(poseAfter({0.0, 0.0, 90.0}, {0.0, 1.0, 0.0}, 2.0), -2.0, 0.0, 90.0);
}

TEST(Motion, TurningOnTheSpotOnlyTurns) {
  expectPose(poseAfter({0.5, -0.5, 10.0}, {0.0, 0.0, 90.0}, 0.25), 0.5, -0.5, 32.5);
}

TEST(Motion, DrivingAndTurningFollowsACircle) {
  // 1 m/s at 90°/s: a circle of radius 2/π m about (0, r), a quarter of it per second.
  const double r = 2.0 / kPi;
  expectPose(poseAfter({0.0, 0.0, 0.0}, {1.0, 0.0, 90.0}, 1.0), r, r, 90.0);
  expectPose(poseAfter({0.0, 0.0, 0.0}, {1.0, 0.0, 90.0}, 2.0), 0.0, 2.0 * r, 180.0);
  expectPose(poseAfter({0.0, 0.0, 0.0}, {1.0, 0.0, 90.0}, 4.0), 0.0, 0.0, 360.0);
  // Clockwise, sideways and rotated start: the same circle through the start's frame.
  const RobotPose p = poseAfter({3.0, 4.0, 90.0}, {0.0, 1.0, -90.0}, 1.0);  // left = world −x, turning right
  expectPose(p, 3.0 - r, 4.0 + r, 0.0);
}

TEST(Motion, TinyTurnsJoinTheStraightLineSmoothly) {
  const RobotPose straight = poseAfter({0.0, 0.0, 20.0}, {1.5, -0.5, 0.0}, 0.1);
  for (double rate : {1e-12, 1e-7, 1e-5, -1e-5}) {
    const RobotPose bent = poseAfter({0.0, 0.0, 20.0}, {1.5, -0.5, rate}, 0.1);
    EXPECT_NEAR(bent.x, straight.x, 1e-8) << rate;
    EXPECT_NEAR(bent.y, straight.y, 1e-8) << rate;
  }
  // Either side of the series' switch the two forms agree to rounding.
  const RobotPose below = poseAfter({0.0, 0.0, 0.0}, {1.0, 1.0, 0.999e-4 / kPi * 180.0}, 1.0);
  const RobotPose above = poseAfter({0.0, 0.0, 0.0}, {1.0, 1.0, 1.001e-4 / kPi * 180.0}, 1.0);
  EXPECT_NEAR(below.x, above.x, 2e-7);
  EXPECT_NEAR(below.y, above.y, 2e-7);
}

TEST(Motion, VelocityBetweenTwoPosesDrivesFromOneToTheOther) {
  const RobotPose from{0.3, -1.2, 200.0};
  for (const BodyVelocity& v : {BodyVelocity{1.0, 0.0, 90.0}, BodyVelocity{-0.4, 0.7, -170.0}, BodyVelocity{0.2, 0.1, 0.0}}) {
    const RobotPose to = poseAfter(from, v, 0.8);
    const BodyVelocity back = velocityBetween(from, to, 0.8);
    EXPECT_NEAR(back.vx, v.vx, 1e-12);
    EXPECT_NEAR(back.vy, v.vy, 1e-12);
    EXPECT_NEAR(back.yawRateDegPerS, v.yawRateDegPerS, 1e-11);
  }
}

TEST(Shutter, StratifiedInstantsCoverEveryStratumOncePerGridRowAndColumn) {
  Shutter shutter{0.01, std::nullopt, 0};
  for (int n = 1; n <= 6; ++n) {
    EXPECT_EQ(pixelInstants(shutter, n).count, n * n);
    EXPECT_EQ(pixelInstants(shutter, n).passes, 1);
    std::set<int> all;
    for (int b = 0; b < n; ++b) {
      std::set<int> rowStrata, columnStrata;
      for (int a = 0; a < n; ++a) {
        all.insert(instantOf(shutter, a, b, n, 0));
        rowStrata.insert(instantOf(shutter, a, b, n, 0) / n);
        columnStrata.insert(instantOf(shutter, b, a, n, 0) / n);
      }
      EXPECT_EQ(rowStrata.size(), static_cast<size_t>(n));
      EXPECT_EQ(columnStrata.size(), static_cast<size_t>(n));
    }
    EXPECT_EQ(all.size(), static_cast<size_t>(n * n));
    EXPECT_EQ(*all.rbegin(), n * n - 1);
  }
  // Instants are the midpoints of equal parts of the exposure.
  EXPECT_DOUBLE_EQ(instantTime(shutter, 0, 4), 0.00125);
  EXPECT_DOUBLE_EQ(instantTime(shutter, 3, 4), 0.00875);
}

TEST(Shutter, FixedTimeSamplesTraceEverySampleAtEachInstant) {
  const Shutter shutter{0.02, std::nullopt, 3};
  EXPECT_EQ(pixelInstants(shutter, 4).count, 3);
  EXPECT_EQ(pixelInstants(shutter, 4).passes, 3);
  for (int pass = 0; pass < 3; ++pass) EXPECT_EQ(instantOf(shutter, 1, 2, 4, pass), pass);
  EXPECT_EQ(pixelInstants(Shutter{}, 4).count, 1);  // no exposure: one instant, t = 0
  EXPECT_EQ(instantTime(Shutter{}, 0, 1), 0.0);
}

TEST(Shutter, RollingLinesStartOneLineTimeApartInTheReadoutDirection) {
  Shutter shutter{0.001, RollingShutter{30.0, Readout::TopToBottom}, 0};
  EXPECT_EQ(lineOf(shutter, 5, 7, 20, 10), 7);
  EXPECT_EQ(lineCount(shutter, 20, 10), 10);
  EXPECT_DOUBLE_EQ(lineStart(shutter, 7), 210e-6);
  EXPECT_DOUBLE_EQ(pixelTime(shutter, 5, 7, 20, 10), 210e-6 + 0.0005);
  EXPECT_DOUBLE_EQ(frameDuration(shutter, 20, 10), 270e-6 + 0.001);
  shutter.rolling->readout = Readout::BottomToTop;
  EXPECT_EQ(lineOf(shutter, 5, 7, 20, 10), 2);
  shutter.rolling->readout = Readout::LeftToRight;
  EXPECT_EQ(lineOf(shutter, 5, 7, 20, 10), 5);
  EXPECT_EQ(lineCount(shutter, 20, 10), 20);
  shutter.rolling->readout = Readout::RightToLeft;
  EXPECT_EQ(lineOf(shutter, 5, 7, 20, 10), 14);
  const Shutter global{0.004, std::nullopt, 0};
  EXPECT_EQ(lineOf(global, 5, 7, 20, 10), 0);
  EXPECT_DOUBLE_EQ(pixelTime(global, 5, 7, 20, 10), 0.002);
  EXPECT_DOUBLE_EQ(frameDuration(global, 20, 10), 0.004);
  for (Readout r : {Readout::TopToBottom, Readout::BottomToTop, Readout::LeftToRight, Readout::RightToLeft})
    EXPECT_EQ(readoutNamed(readoutName(r)), r);
  EXPECT_FALSE(readoutNamed("diagonal"));
}

}  // namespace
}  // namespace omnicam
