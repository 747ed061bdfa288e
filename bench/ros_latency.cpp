// `omnicam ros` as a robot stack sees it (docs/ros.md, docs/performance.md): the time from an
// odometry message published to the camera's image received, at 360 px, one mirror camera, for
// unlit, lit and path shading; and the sustained rate when each pose is sent as soon as the last
// image is in. Its own ROS master (tests/ros_master.h), localhost. Prints a table.
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench_flags.h"
#include "ros_master.h"
#include "statistics.h"
#include "test_daemons.h"

namespace fs = std::filesystem;
using omnicam::testing::RosMaster;
using omnicam::testing::TestDaemons;
using Clock = std::chrono::steady_clock;

namespace {

constexpr int kPoses = 300;

struct Mode {
  const char* name;
  const char* settings;  // the spec's render settings
};

std::string specText(const Mode& mode) {
  return std::string(R"({"format": "omnicam-dataset/1", "scene": ")") + OMNICAM_SOURCE_DIR +
         R"(/scenes/robocup2006.json", "size": 360, )" + mode.settings + R"(, "poses": {"list": [[0, 0, 0]]},
  "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})";
}

double median(std::vector<double> values) { return omnicam::medianOf(std::move(values)).value_or(0.0); }

// Latencies (ms) of kPoses poses sent one at a time, and the whole run's rate.
void measure(const Mode& mode, const fs::path& root, ros::NodeHandle& handle, int index) {
  const fs::path spec = root / ("spec-" + std::to_string(index) + ".json");
  std::ofstream(spec) << specText(mode);
  const std::string robot = "bench" + std::to_string(index);
  TestDaemons node;
  std::vector<std::string> environment;
  for (const char* name : {"ROS_MASTER_URI", "ROS_HOME", "ROS_LOG_DIR", "ROS_IP"})
    if (const char* value = std::getenv(name)) environment.push_back(std::string(name) + "=" + value);
  if (!node.start("omnicam ros",
                  {OMNICAM_BINARY, "ros", spec.string(), "--robot", robot, "--odom", "/" + robot + "/odom", "--frames",
                   std::to_string(kPoses)},
                  root / ("node-" + std::to_string(index) + ".out"), environment)) {
    std::printf("%s: cannot start omnicam ros\n", mode.name);
    return;
  }
  ros::Publisher odometry = handle.advertise<nav_msgs::Odometry>("/" + robot + "/odom", 1);
  // Each image's arrival, taken in the callback; the loop below waits on it without polling.
  std::mutex mutex;
  std::condition_variable arrived;
  std::vector<Clock::time_point> arrivals;
  ros::Subscriber images = handle.subscribe<sensor_msgs::Image>(
      "/" + robot + "/cam0/image_raw", 1, [&](const sensor_msgs::Image::ConstPtr&) {
        {
          std::lock_guard<std::mutex> lock(mutex);
          arrivals.push_back(Clock::now());
        }
        arrived.notify_one();
      });
  if (!TestDaemons::waitFor([&] { return odometry.getNumSubscribers() > 0 && images.getNumPublishers() > 0; }, 120.0)) {
    std::printf("%s: the node never connected\n", mode.name);
    return;
  }
  std::vector<double> latencies;
  const auto start = Clock::now();
  for (int k = 0; k < kPoses; ++k) {
    nav_msgs::Odometry m;
    m.header.stamp = ros::Time(1000 + k, 0);
    m.pose.pose.position.x = 0.01 * (k % 100), m.pose.pose.position.y = 0.5;
    m.pose.pose.orientation.w = 1.0;
    const auto sent = Clock::now();
    odometry.publish(m);
    std::unique_lock<std::mutex> lock(mutex);
    if (!arrived.wait_for(lock, std::chrono::seconds(120), [&] { return arrivals.size() > static_cast<size_t>(k); })) {
      std::printf("%s: no image for pose %d\n", mode.name, k);
      return;
    }
    latencies.push_back(std::chrono::duration<double, std::milli>(arrivals[k] - sent).count());
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  node.waitForExit("omnicam ros", 60.0);
  std::vector<double> sorted = latencies;
  std::sort(sorted.begin(), sorted.end());
  std::printf("%-8s %-46s %8.2f %8.2f %8.2f %10.1f\n", mode.name, mode.settings, sorted.front(), median(latencies),
              sorted[sorted.size() * 9 / 10], kPoses / seconds);
}

}  // namespace

int main(int argc, char** argv) {
  const omnicam::bench::BenchFlags flags(argc, argv, {}, "ros_latency (no options)");
  const fs::path root = fs::temp_directory_path() / ("omnicam_ros_latency_" + std::to_string(::getpid()));
  fs::create_directories(root);
  RosMaster master(root);
  if (!master.problem().empty()) {
    std::fprintf(stderr, "ros_latency: %s\n", master.problem().c_str());
    return 1;
  }
  for (const std::string& variable : master.environment()) ::putenv(::strdup(variable.c_str()));
  int rosArgc = 0;  // ROS remappings are not this benchmark's
  ros::init(rosArgc, nullptr, "ros_latency", ros::init_options::NoSigintHandler | ros::init_options::NoRosout);
  ros::NodeHandle handle;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const Mode modes[] = {{"unlit", R"("spp": 1, "shading": "unlit")"},
                        {"lit", R"("spp": 1, "shading": "lit")"},
                        {"path", R"("spp": 4, "shading": "path", "denoise": true)"}};
  std::printf("omnicam ros, pose published -> image received, 360 px, one mirror camera, %d poses one at a time\n", kPoses);
  std::printf("%-8s %-46s %8s %8s %8s %10s\n", "mode", "settings", "min ms", "median", "p90", "poses/s");
  for (int i = 0; i < 3; ++i) measure(modes[i], root, handle, i);
  spinner.stop();
  ros::shutdown();
  fs::remove_all(root);
  return 0;
}
