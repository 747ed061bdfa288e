// A calibration dataset's Kalibr bag (docs/calibration.md) read by ROS 1's own C++ rosbag, as
// `rosbag play` and C++ nodes read bags: rosbag::View's default query starts at ros::TIME_MIN
// (0 s 1 ns), and Bag::write refuses anything earlier. Every frame must be seen, the first
// (frame 0, stamped 0) included; its header keeps the frame's time.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>

#include <string>
#include <vector>

#include "scratch_folder.h"
#include "shell_command.h"

namespace omnicam {
namespace {

TEST(CalibrationBag, RosbagsOwnReaderSeesEveryFrameTheFirstIncluded) {
  const test_support::ScratchFolder scratch("calibration_bag");
  const std::string out = scratch.file("cal");
  const testing::CommandResult run = testing::runShell(std::string(OMNICAM_BINARY) + " dataset " OMNICAM_SOURCE_DIR
                                                       "/docs/examples/calibration_dataset.json -o " + out + " 2>&1");
  ASSERT_EQ(run.code, 0) << run.out;
  rosbag::Bag bag(out + "/kalibr.bag", rosbag::bagmode::Read);
  std::vector<ros::Time> stamps, recorded;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    const sensor_msgs::Image::ConstPtr image = m.instantiate<sensor_msgs::Image>();
    ASSERT_TRUE(image) << m.getTopic();
    stamps.push_back(image->header.stamp);
    recorded.push_back(m.getTime());
  }
  ASSERT_EQ(stamps.size(), 20u);  // the example's 20 board poses
  for (size_t i = 0; i < stamps.size(); ++i) {
    // frame_interval_s 0.1 (the default): frame i at i × 0.1 s, exactly in ns.
    EXPECT_EQ(stamps[i], ros::Time(static_cast<uint32_t>(i / 10), static_cast<uint32_t>(i % 10) * 100000000u)) << i;
    EXPECT_EQ(recorded[i], i == 0 ? ros::TIME_MIN : stamps[i]) << i;
  }
}

}  // namespace
}  // namespace omnicam
