#include "camera_path.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace omnicam {
namespace {

TEST(CameraPath, EvenArcLengthSpacingAndHeadingAlongSegments) {
  const auto poses = sampleWaypointPath({{0, 0}, {0, -3}, {-4, -3}}, 8);  // length 7
  ASSERT_EQ(poses.size(), 8u);
  EXPECT_DOUBLE_EQ(poses.front().x, 0.0);
  EXPECT_DOUBLE_EQ(poses.back().x, -4.0);
  EXPECT_DOUBLE_EQ(poses.back().y, -3.0);
  EXPECT_DOUBLE_EQ(poses[1].yawDeg, -90.0);
  EXPECT_DOUBLE_EQ(poses[3].x, 0.0);  // s = 3: the corner, heading the outgoing way
  EXPECT_DOUBLE_EQ(poses[3].yawDeg, 180.0);
  for (size_t i = 1; i < poses.size(); ++i) {
    const double step = std::abs(poses[i].x - poses[i - 1].x) + std::abs(poses[i].y - poses[i - 1].y);
    EXPECT_NEAR(step, 1.0, 1e-12);
  }
}

// A waypoint given twice is a segment of no length and no heading of its own: the robot keeps
// the heading it has (at the start: the one it sets off in), never turning to 0° at it.
TEST(CameraPath, ARepeatedWaypointKeepsTheHeading) {
  const auto ending = sampleWaypointPath({{0, 0}, {0, 2}, {0, 2}}, 3);
  for (const RobotPose& p : ending) EXPECT_DOUBLE_EQ(p.yawDeg, 90.0);
  EXPECT_DOUBLE_EQ(ending.back().y, 2.0);
  const auto starting = sampleWaypointPath({{1, 1}, {1, 1}, {-1, 1}, {-1, 1}, {-1, -1}}, 5);
  EXPECT_DOUBLE_EQ(starting.front().yawDeg, 180.0);
  EXPECT_DOUBLE_EQ(starting[1].yawDeg, 180.0);
  EXPECT_DOUBLE_EQ(starting.back().yawDeg, -90.0);
  EXPECT_DOUBLE_EQ(starting.back().y, -1.0);
  for (const RobotPose& p : sampleWaypointPath({{3, 4}, {3, 4}}, 2)) EXPECT_DOUBLE_EQ(p.yawDeg, 0.0);  // nowhere to head
  EXPECT_THROW(sampleWaypointPath({{3, 4}}, 2), std::invalid_argument);
}

}  // namespace
}  // namespace omnicam
