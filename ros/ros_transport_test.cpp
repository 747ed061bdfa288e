// ros1::Transport against a real ROS master the test starts and stops itself: odometry in and
// images out, field by field, a node that outlives its master, and poses asked of tf.
#include "ros_transport.h"

#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <tf2_msgs/TFMessage.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <future>
#include <mutex>
#include <utility>
#include <vector>

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

// Poses asked of tf at stamps: handed over, oldest first, once /tf reaches them (tf2
// interpolating between its data), never before; refused with tf's reason when ROS time is 1 s
// past one the tree has not reached.
TEST(RosTransport, HandsOverTfRequestsOnceTheTreeReachesThem) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_ros_transport_tf_" + std::to_string(::getpid()));
  fs::create_directories(root);
  RosMaster master(root);
  ASSERT_EQ(master.problem(), "");
  for (const std::string& variable : master.environment()) ::putenv(::strdup(variable.c_str()));

  Transport transport("omnicam_transport_tf_test", 60.0);
  std::mutex mutex;  // the handlers run on the spinner thread
  std::vector<Odometry> poses;
  std::vector<std::pair<Stamp, std::string>> gaps;
  TransformHandlers handlers;
  handlers.pose = [&](const Odometry& o) {
    std::lock_guard<std::mutex> lock(mutex);
    poses.push_back(o);
  };
  handlers.gap = [&](const Stamp& stamp, const std::string& why) {
    std::lock_guard<std::mutex> lock(mutex);
    gaps.emplace_back(stamp, why);
  };
  transport.subscribeTransform("map", "base_link", /*eachMove=*/false, handlers);
  const auto counts = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    return std::make_pair(poses.size(), gaps.size());
  };

  ros::NodeHandle node;
  ros::Publisher tf = node.advertise<tf2_msgs::TFMessage>("/tf", 10);
  ASSERT_TRUE(TestDaemons::waitFor([&] { return tf.getNumSubscribers() > 0; }, 60.0));
  const auto robotAt = [&](const std::vector<std::pair<ros::Time, double>>& xs) {
    tf2_msgs::TFMessage m;
    for (const auto& [stamp, x] : xs) {
      geometry_msgs::TransformStamped t;
      t.header.stamp = stamp;
      t.header.frame_id = "map";
      t.child_frame_id = "base_link";
      t.transform.translation.x = x;
      t.transform.rotation.w = 1;
      m.transforms.push_back(t);
    }
    tf.publish(m);
  };
  const auto request = [&](const std::vector<ros::Time>& stamps) {
    transport.post([&transport, stamps] {
      for (const ros::Time& t : stamps) transport.requestTransform({t.sec, t.nsec});
    });
  };
  // ROS time is the wall clock here: stamps 50 s ahead of it do not expire within the test (a
  // request waits until ROS time is 1 s past it), and the tree's data, up to 55 s ahead, is within
  // the 60 s that a transform may be ahead of ROS time (kMostStampAheadSeconds).
  const ros::Time ahead = ros::Time::now() + ros::Duration(50.0);

  // 5 s behind ROS time, with no tf at all: refused at once, with tf's reason.
  const ros::Time behind = ros::Time::now() - ros::Duration(5.0);
  request({behind});
  ASSERT_TRUE(TestDaemons::waitFor([&] { return counts().second == 1; }, 60.0));
  // Ahead, waiting for tf: handed over once the tree has data around it, x interpolated.
  request({ahead});
  robotAt({{ahead - ros::Duration(1.0), 0.0}, {ahead + ros::Duration(1.0), 2.0}});
  ASSERT_TRUE(TestDaemons::waitFor([&] { return counts().first == 1; }, 60.0));
  // Two beyond the tree's data, asked newest first: both handed over, oldest first, by the one
  // message that reaches them (x = 2 + (t − ahead − 1) between the samples at +1 s and +5 s).
  request({ahead + ros::Duration(3.0), ahead + ros::Duration(2.0)});
  robotAt({{ahead + ros::Duration(5.0), 6.0}});
  ASSERT_TRUE(TestDaemons::waitFor([&] { return counts().first == 3; }, 60.0));

  std::lock_guard<std::mutex> lock(mutex);
  EXPECT_EQ(gaps[0].first.sec, behind.sec);
  EXPECT_NE(gaps[0].second.find("map"), std::string::npos) << gaps[0].second;  // tf2: the frame does not exist
  const double expectedX[] = {1.0, 3.0, 4.0};
  const ros::Time expectedStamp[] = {ahead, ahead + ros::Duration(2.0), ahead + ros::Duration(3.0)};
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(poses[k].stamp.sec, expectedStamp[k].sec) << k;
    EXPECT_EQ(poses[k].stamp.nsec, expectedStamp[k].nsec) << k;
    EXPECT_DOUBLE_EQ(poses[k].position[0], expectedX[k]) << k;
    EXPECT_EQ(poses[k].frame, "map");
  }
  EXPECT_EQ(gaps.size(), 1u);
  fs::remove_all(root);
}

}  // namespace
}  // namespace omnicam::ros1
