#include "trajectory.h"

#include <gtest/gtest.h>

#include <cmath>

namespace omnicam {
namespace {

void expectPose(const RobotPose& got, double x, double y, double yawDeg) {
  EXPECT_NEAR(got.x, x, 1e-12);
  EXPECT_NEAR(got.y, y, 1e-12);
  EXPECT_NEAR(got.yawDeg, yawDeg, 1e-9);
}

TEST(Trajectory, AtASpeedEachSegmentTakesItsDistanceOrItsTurnWhicheverIsSlower) {
  // Drive 1 m, turn 90° on the spot, drive 1 m: at 0.5 m/s and 45°/s, 2 s each.
  const Trajectory t = Trajectory::atSpeed({{0, 0, 0}, {1, 0, 0}, {1, 0, 90}, {1, 1, 90}}, 0.5, 45.0);
  EXPECT_DOUBLE_EQ(t.end(), 6.0);
  expectPose(t.poseAt(1.0), 0.5, 0.0, 0.0);
  expectPose(t.poseAt(3.0), 1.0, 0.0, 45.0);
  expectPose(t.poseAt(5.0), 1.0, 0.5, 90.0);
  EXPECT_EQ(t.velocityAt(1.0), (BodyVelocity{0.5, 0.0, 0.0}));
  EXPECT_NEAR(t.velocityAt(3.0).yawRateDegPerS, 45.0, 1e-12);
  EXPECT_NEAR(t.velocityAt(5.0).vx, 0.5, 1e-12);
  // Moving 1 m while turning 90° at 1 m/s and 30°/s: the turn takes longer, 3 s.
  EXPECT_NEAR(Trajectory::atSpeed({{0, 0, 0}, {1, 0, 90}}, 1.0, 30.0).end(), 3.0, 1e-12);
  // At 0.25 m/s the same segment is an arc whose length is longer than its 1 m chord.
  const double arc = (kPi / 2) * (0.5 / std::sin(kPi / 4));  // chord 1 subtends 90° on radius 1/√2
  EXPECT_NEAR(Trajectory::atSpeed({{0, 0, 0}, {1, 0, 90}}, 0.25, 90.0).end(), arc / 0.25, 1e-12);
}

TEST(Trajectory, TimestampsDriveEachSegmentAlongItsArc) {
  // A quarter circle of radius 2 about (0, 2) in 4 s, then straight on for 1 s at 3 m/s.
  const Trajectory t({{0, 0, 0}, {2, 2, 90}, {2, 5, 90}}, {10.0, 14.0, 15.0});
  EXPECT_DOUBLE_EQ(t.start(), 10.0);
  EXPECT_DOUBLE_EQ(t.end(), 15.0);
  const BodyVelocity v = t.velocityAt(11.0);
  EXPECT_NEAR(v.vx, 2.0 * (kPi / 2) / 4.0, 1e-12);
  EXPECT_NEAR(v.vy, 0.0, 1e-12);
  EXPECT_NEAR(v.yawRateDegPerS, 22.5, 1e-12);
  expectPose(t.poseAt(12.0), 2.0 * std::sin(kPi / 4), 2.0 - 2.0 * std::cos(kPi / 4), 45.0);
  expectPose(t.poseAt(14.5), 2.0, 3.5, 90.0);
  EXPECT_NEAR(t.velocityAt(14.5).vx, 3.0, 1e-12);
  // Clamped outside [start, end]; the last segment's velocity holds from the end on.
  expectPose(t.poseAt(0.0), 0.0, 0.0, 0.0);
  expectPose(t.poseAt(99.0), 2.0, 5.0, 90.0);
  EXPECT_NEAR(t.velocityAt(99.0).vx, 3.0, 1e-12);
}

TEST(Trajectory, RepeatedWaypointsAndASingleOneAddNoTime) {
  const Trajectory repeated = Trajectory::atSpeed({{0, 0, 0}, {0, 0, 0}, {2, 0, 0}, {2, 0, 360}}, 1.0, 90.0);
  EXPECT_DOUBLE_EQ(repeated.end(), 2.0);  // 360° is no turn: the shorter way round
  expectPose(repeated.poseAt(1.0), 1.0, 0.0, 0.0);
  const Trajectory single = Trajectory::atSpeed({{1, 2, 3}}, 1.0, 90.0);
  EXPECT_DOUBLE_EQ(single.end(), 0.0);
  expectPose(single.poseAt(5.0), 1.0, 2.0, 3.0);
  EXPECT_TRUE(single.velocityAt(0.0).still());
}

}  // namespace
}  // namespace omnicam
