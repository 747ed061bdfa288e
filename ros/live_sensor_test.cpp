// `omnicam ros SPEC` end to end against a ROS master the test starts and stops itself: poses
// published on odometry, the images of two cameras received, each equal byte for byte to the
// frame `omnicam dataset` renders for the same spec and poses (the front camera with a rolling
// shutter, so that the odometry's twist shows).
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ros_master.h"
#include "shell_command.h"
#include "test_daemons.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using testing::RosMaster;
using testing::TestDaemons;
using testing::CommandResult;
using testing::readFile;
using testing::runShell;

struct SentPose {
  double x, y;
  double qz, qw;  // yaw 0 or 180°, whose angle the node's atan2 gives exactly
  double yawDeg;
};
const SentPose kPoses[] = {{1.0, -0.5, 0.0, 1.0, 0.0}, {2.0, 1.0, 1.0, 0.0, 180.0}, {-1.5, 0.25, 0.0, 1.0, 0.0}};
constexpr double kForward = 0.5, kYawRateRadPerS = 0.3;
const char* kCameras[] = {"front", "rear"};

// The scene's rig with a rolling shutter: the front camera's frames then depend on the twist.
std::string rollingShutterRig() {
  nlohmann::json rig = nlohmann::json::parse(readFile(fs::path(OMNICAM_SOURCE_DIR) / "scenes/robocup2006.json")).at("rig");
  rig["shutter"] = {{"exposure_s", 0.02}, {"rolling", {{"line_time_us", 200}, {"readout", "top-to-bottom"}}}};
  return rig.dump();
}

// The dataset spec both runs read: the poses above as a list, the twist as the motion.
std::string specText() {
  std::ostringstream poses;
  for (const SentPose& p : kPoses) poses << (poses.tellp() > 0 ? ", " : "") << "[" << p.x << ", " << p.y << ", " << p.yawDeg << "]";
  char yawRate[64];
  std::snprintf(yawRate, sizeof yawRate, "%.17g", kYawRateRadPerS * (180.0 / M_PI));  // the node's conversion
  return std::string(R"({"format": "omnicam-dataset/1", "scene": ")") + OMNICAM_SOURCE_DIR +
         R"(/scenes/robocup2006.json", "size": 96, "spp": 4, "shading": "lit",
  "poses": {"list": [)" + poses.str() + R"(]}, "motion": {"velocity": [)" + std::to_string(kForward) + ", 0, " + yawRate +
         R"(]},
  "cameras": [{"name": "front", "mount": {"x": 0.1, "y": 0, "yaw_deg": 0}, "rig": )" + rollingShutterRig() + R"(},
              {"name": "rear", "mount": {"x": -0.1, "y": 0, "yaw_deg": 180}}],
  "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})";
}

// The dataset's frame as rgb8 bytes, row by row.
std::vector<uint8_t> datasetRgb8(const fs::path& dataset, const std::string& camera, int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.png", frame);
  const cv::Mat bgra = cv::imread((dataset / camera / "rgb" / name).string(), cv::IMREAD_UNCHANGED);
  cv::Mat rgb;
  cv::cvtColor(bgra, rgb, bgra.channels() == 4 ? cv::COLOR_BGRA2RGB : cv::COLOR_BGR2RGB);
  return std::vector<uint8_t>(rgb.data, rgb.data + rgb.total() * 3);
}

TEST(LiveSensor, RendersEveryOdometryPoseAsTheDatasetDoesForTwoCameras) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_live_sensor_test_" + std::to_string(::getpid()));
  fs::create_directories(root);
  std::ofstream(root / "spec.json") << specText();
  const CommandResult dataset = runShell(std::string(OMNICAM_BINARY) + " dataset " + (root / "spec.json").string() +
                                         " -o " + (root / "dataset").string() + " 2>&1");
  ASSERT_EQ(dataset.code, 0) << dataset.out;

  RosMaster master(root);
  ASSERT_EQ(master.problem(), "");
  TestDaemons node;
  ASSERT_TRUE(node.start("omnicam ros",
                         {OMNICAM_BINARY, "ros", (root / "spec.json").string(), "--robot", "bot", "--odom", "/bot/odom",
                          "--frames", std::to_string(std::size(kPoses))},
                         root / "node.out", master.environment()));

  for (const std::string& variable : master.environment()) ::putenv(::strdup(variable.c_str()));
  int argc = 0;
  ros::init(argc, nullptr, "live_sensor_test", ros::init_options::NoSigintHandler | ros::init_options::NoRosout);
  ros::NodeHandle handle;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  ros::Publisher odometry = handle.advertise<nav_msgs::Odometry>("/bot/odom", 10);
  std::mutex mutex;
  std::map<std::string, std::vector<sensor_msgs::Image>> received;
  std::vector<ros::Subscriber> subscriptions;
  for (const std::string camera : kCameras)
    subscriptions.push_back(handle.subscribe<sensor_msgs::Image>(
        "/bot/" + camera + "/image_raw", 10, [&, camera](const sensor_msgs::Image::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          received[camera].push_back(*m);
        }));
  const auto count = [&](const std::string& camera) {
    std::lock_guard<std::mutex> lock(mutex);
    return received[camera].size();
  };
  // The node is up when it listens to the odometry and both image topics are connected.
  ASSERT_TRUE(TestDaemons::waitFor(
      [&] {
        return odometry.getNumSubscribers() > 0 && subscriptions[0].getNumPublishers() > 0 &&
               subscriptions[1].getNumPublishers() > 0;
      },
      120.0))
      << readFile(root / "node.out");

  // One pose at a time, each sent once the last one's images are in: nothing is dropped.
  for (size_t k = 0; k < std::size(kPoses); ++k) {
    nav_msgs::Odometry m;
    m.header.stamp = ros::Time(100 + static_cast<uint32_t>(k), 250);
    m.header.frame_id = "odom";
    m.child_frame_id = "base_link";
    m.pose.pose.position.x = kPoses[k].x, m.pose.pose.position.y = kPoses[k].y;
    m.pose.pose.orientation.z = kPoses[k].qz, m.pose.pose.orientation.w = kPoses[k].qw;
    m.twist.twist.linear.x = kForward, m.twist.twist.angular.z = kYawRateRadPerS;
    odometry.publish(m);
    ASSERT_TRUE(TestDaemons::waitFor([&] { return count("front") > k && count("rear") > k; }, 300.0))
        << "pose " << k << ": " << readFile(root / "node.out");
  }
  ASSERT_EQ(node.waitForExit("omnicam ros", 120.0), 0) << readFile(root / "node.out");
  EXPECT_NE(readFile(root / "node.out").find("3 poses rendered, 0 dropped"), std::string::npos) << readFile(root / "node.out");

  for (const std::string camera : kCameras)
    for (size_t k = 0; k < std::size(kPoses); ++k) {
      const sensor_msgs::Image& image = received[camera][k];
      SCOPED_TRACE(camera + " pose " + std::to_string(k));
      EXPECT_EQ(image.header.stamp, ros::Time(100 + static_cast<uint32_t>(k), 250));
      EXPECT_EQ(image.header.frame_id, camera);
      EXPECT_EQ(image.encoding, "rgb8");
      EXPECT_EQ(image.width, 96u);
      EXPECT_EQ(image.height, 96u);
      EXPECT_EQ(image.step, 96u * 3);
      EXPECT_TRUE(image.data == datasetRgb8(root / "dataset", camera, static_cast<int>(k)));
    }
  spinner.stop();
  ros::shutdown();
  fs::remove_all(root);
}

}  // namespace
}  // namespace omnicam
