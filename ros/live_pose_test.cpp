// An odometry message as the sensor's pose, and the messages it refuses: closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "live_sensor.h"

namespace omnicam {
namespace {

ros1::Odometry turnedBy(double yawRad) {
  ros1::Odometry o;
  o.stamp = {5, 7};
  o.position[0] = 3.5, o.position[1] = -1.25;
  o.orientationXyzw[2] = std::sin(yawRad / 2), o.orientationXyzw[3] = std::cos(yawRad / 2);
  o.linear[0] = 0.8, o.linear[1] = -0.1, o.angular[2] = M_PI / 4;
  return o;
}

TEST(LivePose, YawComesFromTheQuaternionAndTheTwistIsTheVelocity) {
  for (const double yawDeg : {0.0, 30.0, 90.0, 179.0, -135.0}) {
    const LivePose live = livePoseOf(turnedBy(yawDeg * M_PI / 180.0));
    EXPECT_NEAR(live.pose.yawDeg, yawDeg, 1e-12);
    EXPECT_EQ(live.pose.x, 3.5);
    EXPECT_EQ(live.pose.y, -1.25);
    EXPECT_EQ(live.velocity.vx, 0.8);
    EXPECT_EQ(live.velocity.vy, -0.1);
    EXPECT_NEAR(live.velocity.yawRateDegPerS, 45.0, 1e-12);
    EXPECT_EQ(live.stamp.sec, 5u);
    EXPECT_EQ(live.stamp.nsec, 7u);
  }
}

TEST(LivePose, HostileMessagesAreRefusedWithTheirReason) {
  const ros1::Stamp last{5, 7};
  EXPECT_EQ(problemWith(turnedBy(0.3), &last), "its stamp 5.000000007 is not after the last pose's, 5.000000007");
  EXPECT_EQ(problemWith(turnedBy(0.3), nullptr), "");
  const ros1::Stamp earlier{5, 6};
  EXPECT_EQ(problemWith(turnedBy(0.3), &earlier), "");
  ros1::Odometry o = turnedBy(0.3);
  o.angular[2] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(problemWith(o, nullptr), "a number of the pose or twist is not finite");
  o = turnedBy(0.3);
  o.orientationXyzw[3] = 0.5;
  EXPECT_EQ(problemWith(o, nullptr), "the orientation is not a unit quaternion");
  o = turnedBy(0.3);
  o.position[1] = -10000.5;
  EXPECT_EQ(problemWith(o, nullptr), "the position is beyond ±10 km");
  o = turnedBy(0.3);
  o.stamp = {0, 0};
  EXPECT_EQ(problemWith(o, nullptr), "its stamp is zero (set header.stamp, e.g. rostopic pub -s with stamp: now)");
  o = turnedBy(0.3);
  o.linear[0] = 80.0, o.linear[1] = 61.0;
  EXPECT_EQ(problemWith(o, nullptr), "the speed is above 100 m/s");
  o = turnedBy(0.3);
  o.angular[2] = 628.0;  // 35982 degrees/s: within 100 turns a second
  EXPECT_EQ(problemWith(o, nullptr), "");
  o.angular[2] = -629.0;
  EXPECT_EQ(problemWith(o, nullptr), "the yaw rate is above 36000 degrees/s (628.319 rad/s)");
  // A stamp far after ROS time now (a clock set wrong, a hostile message) would hold every later
  // pose back: refused. Up to a minute ahead is taken (clocks of two machines), and so is any
  // stamp before /clock's first message (ROS time zero).
  o = turnedBy(0.3);
  o.stamp = {4294967295u, 999999999u};
  EXPECT_EQ(problemWith(o, nullptr, {1000, 0}),
            "its stamp 4294967295.999999999 is more than 60 s after ROS time now, 1000.000000000 (a clock that far ahead would "
            "hold every later pose back)");
  EXPECT_EQ(problemWith(o, nullptr, {}), "");
  o.stamp = {1060, 0};
  EXPECT_EQ(problemWith(o, nullptr, {1000, 0}), "");
  o.stamp = {1060, 1};
  EXPECT_NE(problemWith(o, nullptr, {1000, 0}), "");
}

// A slow render drops stale poses instead of queueing them: the newest wins, each replaced one
// counted; a pose taken is gone.
TEST(NewestPose, KeepsOnlyTheNewestAndCountsTheDropped) {
  NewestPose newest;
  EXPECT_FALSE(newest.take(std::chrono::milliseconds(0)).has_value());
  LivePose pose;
  for (uint32_t k = 1; k <= 3; ++k) {
    pose.stamp = {k, 0};
    EXPECT_EQ(newest.put(pose), k > 1);
  }
  EXPECT_EQ(newest.dropped(), 2);
  const std::optional<LivePose> taken = newest.take(std::chrono::milliseconds(0));
  ASSERT_TRUE(taken.has_value());
  EXPECT_EQ(taken->stamp.sec, 3u);
  EXPECT_FALSE(newest.take(std::chrono::milliseconds(0)).has_value());
  pose.stamp = {4, 0};
  EXPECT_FALSE(newest.put(pose));  // nothing was waiting: nothing dropped
  EXPECT_EQ(newest.dropped(), 2);
}

// A repeating event thins out on /diagnostics: logarithmically, then at a fixed stride.
TEST(LiveDiagnostics, ARepeatingEventIsSaidAtPowersOfTwoThenEvery1024th) {
  std::vector<int64_t> said;
  for (int64_t count = 0; count <= 5000; ++count)
    if (saysRepeat(count)) said.push_back(count);
  EXPECT_EQ(said, (std::vector<int64_t>{1, 2, 4, 8, 16, 32, 64, 128, 256, 512, 1024, 2048, 3072, 4096}));
}

// A fixed-rate camera's ticks lie on the grid of its period from the epoch.
TEST(LiveTick, IsTheGridPointAtOrBeforeNow) {
  const ros1::Stamp quarter = tickAtOrBefore({100, 300000000}, 250000000);
  EXPECT_EQ(quarter.sec, 100u);
  EXPECT_EQ(quarter.nsec, 250000000u);
  const ros1::Stamp onTheGrid = tickAtOrBefore({100, 250000000}, 250000000);
  EXPECT_EQ(onTheGrid.nsec, 250000000u);
  // 30 Hz: 33333333 ns; 1 s is past the 30th tick, 999999990 ns.
  const ros1::Stamp thirty = tickAtOrBefore({1, 0}, 33333333);
  EXPECT_EQ(thirty.sec, 0u);
  EXPECT_EQ(thirty.nsec, 999999990u);
}

// The newest pose carried to a tick with its velocity: a straight line, and an arc of a quarter
// turn (radius v/ω), against closed forms; too far from the tick, nothing, with why.
TEST(LiveTick, CarriesTheNewestPoseToTheTickWithItsTwist) {
  LivePose latest;
  latest.stamp = {10, 0};
  latest.pose = {1.0, 2.0, 90.0};
  latest.velocity = {1.0, 0.0, 0.0};
  std::string problem;
  const std::optional<LivePose> ahead = poseAtTick(latest, {10, 400000000}, 0.5, problem);
  ASSERT_TRUE(ahead.has_value()) << problem;
  EXPECT_NEAR(ahead->pose.x, 1.0, 1e-12);  // facing +y: x stays
  EXPECT_NEAR(ahead->pose.y, 2.4, 1e-12);
  EXPECT_EQ(ahead->stamp.nsec, 400000000u);
  EXPECT_EQ(ahead->velocity, latest.velocity);
  const std::optional<LivePose> behind = poseAtTick(latest, {9, 800000000}, 0.5, problem);
  ASSERT_TRUE(behind.has_value());
  EXPECT_NEAR(behind->pose.y, 1.8, 1e-12);

  latest.pose = {0.0, 0.0, 0.0};
  latest.velocity = {1.0, 0.0, 90.0};  // a quarter turn a second on a circle of radius 2/π m
  const std::optional<LivePose> arc = poseAtTick(latest, {10, 500000000}, 0.5, problem);
  ASSERT_TRUE(arc.has_value());
  const double radius = 1.0 / (M_PI / 2);
  EXPECT_NEAR(arc->pose.x, radius * std::sin(M_PI / 4), 1e-12);
  EXPECT_NEAR(arc->pose.y, radius * (1 - std::cos(M_PI / 4)), 1e-12);
  EXPECT_NEAR(arc->pose.yawDeg, 45.0, 1e-12);

  EXPECT_FALSE(poseAtTick(latest, {10, 600000000}, 0.5, problem).has_value());
  EXPECT_EQ(problem, "the newest pose, at 10.000000000, is 0.600 s from the tick at 10.600000000 (more than 0.5 s)");
}

}  // namespace
}  // namespace omnicam
