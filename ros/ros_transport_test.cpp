// ros1::Transport against a real ROS master the test starts and stops itself: odometry in and
// images out, field by field, and a node that outlives its master.
#include "ros_transport.h"

#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <future>

#include "ros_master.h"
#include "test_daemons.h"

namespace omnicam::ros1 {
namespace {

namespace fs = std::filesystem;
using testing::RosMaster;
using testing::TestDaemons;

// ros::init holds for the whole process: one test, one node.
TEST(RosTransport, CarriesOdometryInAndImagesOutThroughItsOwnMaster) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_ros_transport_test_" + std::to_string(::getpid()));
  fs::create_directories(root);
  RosMaster master(root);
  ASSERT_EQ(master.problem(), "");
  for (const std::string& variable : master.environment()) ::putenv(::strdup(variable.c_str()));

  Transport transport("omnicam_transport_test", 60.0);
  std::promise<Odometry> odometry;
  bool first = true;
  transport.subscribeOdometry("/robot/odom", [&](const Odometry& o) {
    if (std::exchange(first, false)) odometry.set_value(o);
  });
  const std::string imageTopic = "/robot/front/image_raw";
  transport.advertiseImage(imageTopic);

  ros::NodeHandle node;
  ros::Publisher odometryOut = node.advertise<nav_msgs::Odometry>("/robot/odom", 1);
  std::promise<sensor_msgs::Image> image;
  bool firstImage = true;
  ros::Subscriber imageIn = node.subscribe<sensor_msgs::Image>(imageTopic, 1, [&](const sensor_msgs::Image::ConstPtr& m) {
    if (std::exchange(firstImage, false)) image.set_value(*m);
  });
  ASSERT_TRUE(TestDaemons::waitFor(
      [&] { return odometryOut.getNumSubscribers() > 0 && transport.subscribers(imageTopic) > 0; }, 60.0));

  nav_msgs::Odometry sent;
  sent.header.stamp = ros::Time(12, 345);
  sent.header.frame_id = "odom";
  sent.child_frame_id = "base_link";
  sent.pose.pose.position.x = 1.5, sent.pose.pose.position.y = -2.25;
  sent.pose.pose.orientation.z = std::sin(0.25), sent.pose.pose.orientation.w = std::cos(0.25);
  sent.twist.twist.linear.x = 0.75, sent.twist.twist.angular.z = -0.5;
  odometryOut.publish(sent);
  auto received = odometry.get_future();
  ASSERT_EQ(received.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  const Odometry o = received.get();
  EXPECT_EQ(o.stamp.sec, 12u);
  EXPECT_EQ(o.stamp.nsec, 345u);
  EXPECT_EQ(o.frame, "odom");
  EXPECT_EQ(o.childFrame, "base_link");
  EXPECT_EQ(o.position[0], 1.5);
  EXPECT_EQ(o.position[1], -2.25);
  EXPECT_EQ(o.orientationXyzw[2], std::sin(0.25));
  EXPECT_EQ(o.orientationXyzw[3], std::cos(0.25));
  EXPECT_EQ(o.linear[0], 0.75);
  EXPECT_EQ(o.angular[2], -0.5);

  Image out;
  out.stamp = {7, 8};
  out.frame = "front_optical";
  out.width = 2, out.height = 1, out.step = 6;
  out.encoding = "rgb8";
  out.data = {1, 2, 3, 250, 251, 252};
  transport.publish(imageTopic, out);
  auto arrived = image.get_future();
  ASSERT_EQ(arrived.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  const sensor_msgs::Image m = arrived.get();
  EXPECT_EQ(m.header.stamp, ros::Time(7, 8));
  EXPECT_EQ(m.header.frame_id, "front_optical");
  EXPECT_EQ(m.width, 2u);
  EXPECT_EQ(m.height, 1u);
  EXPECT_EQ(m.step, 6u);
  EXPECT_EQ(m.encoding, "rgb8");
  EXPECT_EQ(m.data, out.data);

  // The master goes away: the node notices, and publishing does not fail.
  master.stop();
  EXPECT_FALSE(ros::master::check());
  transport.publish(imageTopic, out);
  fs::remove_all(root);
}

}  // namespace
}  // namespace omnicam::ros1
