#include "camera_path.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace omnicam
