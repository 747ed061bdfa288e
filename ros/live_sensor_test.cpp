// `omnicam ros SPEC` end to end against a ROS master the test starts and stops itself: poses
// published on odometry, the images of two cameras received, each equal byte for byte to the
// frame `omnicam dataset` renders for the same spec and poses (the front camera with a rolling
// shutter, so that the odometry's twist shows), each camera_info equal to the dataset's
// intrinsics files, the fisheye's as image_geometry reads it.
#include <diagnostic_msgs/DiagnosticArray.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/network.h>
#include <xmlrpcpp/XmlRpcClient.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosgraph_msgs/Clock.h>
#include <rosbag/view.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <tf2_msgs/TFMessage.h>
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <image_geometry/pinhole_camera_model.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/persistence.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "image.h"
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
// 50 poses over the field, facing one way or the other; every number exact in binary and in the
// spec's decimal text.
std::vector<SentPose> fiftyPoses() {
  std::vector<SentPose> poses;
  for (int k = 0; k < 50; ++k) {
    const bool turned = k % 2 == 1;
    poses.push_back({-2.0 + 0.25 * (k % 16), -1.0 + 0.5 * (k % 5), turned ? 1.0 : 0.0, turned ? 0.0 : 1.0, turned ? 180.0 : 0.0});
  }
  return poses;
}
const std::vector<SentPose> kPoses = fiftyPoses();
constexpr double kForward = 0.5, kYawRateRadPerS = 0.3;
const char* kCameras[] = {"front", "rear", "fisheye"};
// Each camera's image topics: the colour and the planes the spec's outputs ask for.
const char* kImageLeaves[] = {"image_raw", "depth", "instance", "semantic", "normal"};

// The scene's rig with a rolling shutter: the front camera's frames then depend on the twist.
std::string rollingShutterRig() {
  nlohmann::json rig = nlohmann::json::parse(readFile(fs::path(OMNICAM_SOURCE_DIR) / "scenes/robocup2006.json")).at("rig");
  rig["shutter"] = {{"exposure_s", 0.02}, {"rolling", {{"line_time_us", 200}, {"readout", "top-to-bottom"}}}};
  return rig.dump();
}

// The first `count` poses above as a spec's pose list.
std::string poseList(size_t count) {
  std::ostringstream poses;
  for (size_t k = 0; k < count; ++k)
    poses << (k > 0 ? ", " : "") << "[" << kPoses[k].x << ", " << kPoses[k].y << ", " << kPoses[k].yawDeg << "]";
  return R"("poses": {"list": [)" + poses.str() + "]}";
}

// The dataset spec both runs read: the poses above as a list, the twist as the motion.
std::string specText() {
  char yawRate[64];
  std::snprintf(yawRate, sizeof yawRate, "%.17g", kYawRateRadPerS * (180.0 / M_PI));  // the node's conversion
  return std::string(R"({"format": "omnicam-dataset/1", "scene": ")") + OMNICAM_SOURCE_DIR +
         R"(/scenes/robocup2006.json", "size": 96, "spp": 4, "shading": "lit",
  )" + poseList(kPoses.size()) + R"(, "motion": {"velocity": [)" + std::to_string(kForward) + ", 0, " + yawRate +
         R"(]},
  "robot": {"tilt_deg": [2.5, -1.5]},
  "cameras": [{"name": "front", "mount": {"x": 0.1, "y": 0, "yaw_deg": 0}, "rig": )" + rollingShutterRig() + R"(},
              {"name": "rear", "mount": {"x": -0.1, "y": 0, "yaw_deg": 180}},
              {"name": "fisheye", "mount": {"x": 0, "y": 0.1, "yaw_deg": 90}, "rig": {"height": 0.3, "lens":
                {"model": "kannala_brandt", "width": 320, "height": 240, "fx": 95, "fy": 95,
                 "k": [0.02, -0.005, 0.001, 0], "max_theta_deg": 100}}}],
  "outputs": {"rgb": "png", "depth": true, "instance": true, "semantic": true, "normal": true, "landmarks": false}})";
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

template <typename T>
std::vector<T> valuesOf(const sensor_msgs::Image& image) {
  std::vector<T> values(image.data.size() / sizeof(T));
  std::memcpy(values.data(), image.data.data(), image.data.size());
  return values;
}

// The planes' messages against the dataset's files of the frame: depth (32FC1) and the ids
// (16UC1) value for value; the normals (32FC3) as the file's half floats hold them.
void expectPlanesOfTheFiles(std::map<std::string, std::vector<sensor_msgs::Image>>& received, const std::string& camera,
                            int frame, const fs::path& dataset) {
  char name[16];
  std::snprintf(name, sizeof name, "%06d", frame);
  const auto file = [&](const char* kind, const char* extension) {
    return (dataset / camera / kind / (std::string(name) + extension)).string();
  };
  const sensor_msgs::Image& depth = received[camera + "/depth"][frame];
  EXPECT_EQ(depth.encoding, "32FC1");
  EXPECT_EQ(valuesOf<float>(depth), readDataExr(file("depth", ".exr")).values);
  for (const char* kind : {"instance", "semantic"}) {
    const sensor_msgs::Image& ids = received[camera + "/" + kind][frame];
    int width = 0, height = 0;
    EXPECT_EQ(ids.encoding, "16UC1");
    EXPECT_EQ(valuesOf<uint16_t>(ids), readUint16Png(file(kind, ".png"), width, height)) << kind;
    EXPECT_EQ(ids.step, static_cast<uint32_t>(width) * 2) << kind;
  }
  const sensor_msgs::Image& normal = received[camera + "/normal"][frame];
  EXPECT_EQ(normal.encoding, "32FC3");
  const std::vector<float> normals = valuesOf<float>(normal);
  cv::Mat asHalf;
  cv::Mat(1, static_cast<int>(normals.size()), CV_32F, const_cast<float*>(normals.data())).convertTo(asHalf, CV_16F);
  cv::Mat back;
  asHalf.convertTo(back, CV_32F);
  EXPECT_EQ(std::vector<float>(back.begin<float>(), back.end<float>()), readDataExr(file("normal", ".exr")).values);
}

// A camera's frame on /tf_static against the dataset's poses.tum: at frame 0 the robot stands at
// kPoses[0] (yaw 0), so world_from_camera there is the mount (on the tilted robot) moved by the
// pose's x and y.
void expectMountOfTheTumPoses(const geometry_msgs::TransformStamped& mount, const fs::path& tum) {
  SCOPED_TRACE(mount.child_frame_id);
  EXPECT_EQ(mount.header.frame_id, "base_link");
  std::istringstream lines(readFile(tum));
  std::string line;
  while (std::getline(lines, line) && line.rfind('#', 0) == 0) {
  }
  double t = 0, x = 0, y = 0, z = 0, qx = 0, qy = 0, qz = 0, qw = 0;
  ASSERT_EQ(std::sscanf(line.c_str(), "%lf %lf %lf %lf %lf %lf %lf %lf", &t, &x, &y, &z, &qx, &qy, &qz, &qw), 8) << line;
  const auto& m = mount.transform;
  EXPECT_NEAR(m.translation.x, x - kPoses[0].x, 1e-9);
  EXPECT_NEAR(m.translation.y, y - kPoses[0].y, 1e-9);
  EXPECT_NEAR(m.translation.z, z, 1e-9);
  const double dot = m.rotation.x * qx + m.rotation.y * qy + m.rotation.z * qz + m.rotation.w * qw;
  EXPECT_NEAR(std::abs(dot), 1.0, 1e-9);  // the same rotation (q and -q are one)
}

// The bag `omnicam ros --record` wrote: every camera's colour frames equal the dataset's, with
// their camera_info and the cameras' frames on /tf_static.
void expectTheBagHoldsTheDataset(const fs::path& path, const fs::path& dataset) {
  rosbag::Bag bag(path.string(), rosbag::bagmode::Read);
  std::map<std::string, std::vector<sensor_msgs::Image>> images;
  std::map<std::string, size_t> messages;
  std::vector<std::pair<std::string, ros::Time>> order;  // topic and bag time, as rosbag play sends them
  size_t latched = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    ++messages[m.getTopic()];
    order.emplace_back(m.getTopic(), m.getTime());
    // /tf_static and the intrinsics texts are latched, as `rosbag record` marks them: `rosbag play`
    // latches them again for the subscribers that come late. Nothing else is.
    const boost::shared_ptr<const ros::M_string> connection = m.getConnectionHeader();
    const bool latching = connection && connection->count("latching") && connection->at("latching") == "1";
    const bool latchedTopic = m.getTopic() == "/tf_static" || m.getDataType() == "std_msgs/String";
    EXPECT_EQ(latching, latchedTopic) << m.getTopic();
    latched += latchedTopic;
    // Every connection says its type, as rosbag play needs to publish it again.
    EXPECT_FALSE(m.getDataType().empty() || m.getMD5Sum().empty() || m.getMessageDefinition().empty()) << m.getTopic();
    if (m.getTopic() == "/tf_static") {
      EXPECT_NE(m.instantiate<tf2_msgs::TFMessage>(), nullptr);
    }
    if (const sensor_msgs::Image::ConstPtr image = m.instantiate<sensor_msgs::Image>(); image && image->encoding == "rgb8")
      images[m.getTopic()].push_back(*image);
  }
  EXPECT_EQ(messages["/tf_static"], 1u);
  EXPECT_EQ(latched, 1u);  // /tf_static (these cameras have no intrinsics text)
  // The static transforms are at the first pose's stamp, the bag's start (not the wall clock's
  // time, which rosbag play would reach decades later).
  ASSERT_FALSE(order.empty());
  EXPECT_EQ(order[0].second, ros::Time(100, 250));
  for (const auto& [topic, time] : order)
    if (topic == "/tf_static") {
      EXPECT_EQ(time, ros::Time(100, 250));
    }
  for (const std::string camera : kCameras) {
    SCOPED_TRACE(camera);
    EXPECT_EQ(messages["/bot/" + camera + "/camera_info"], std::size(kPoses));
    const std::vector<sensor_msgs::Image>& frames = images["/bot/" + camera + "/image_raw"];
    ASSERT_EQ(frames.size(), std::size(kPoses));
    for (size_t k = 0; k < frames.size(); ++k)
      EXPECT_TRUE(frames[k].data == datasetRgb8(dataset, camera, static_cast<int>(k))) << "pose " << k;
  }
}

// This process's ROS node, once: each test runs in a process of its own (gtest_discover_tests),
// with the master it started.
void startRos(const RosMaster& master) {
  for (const std::string& variable : master.environment()) ::putenv(::strdup(variable.c_str()));
  int argc = 0;
  ros::init(argc, nullptr, "live_sensor_test", ros::init_options::NoSigintHandler | ros::init_options::NoRosout);
}

cv::Mat matrixOf(const double* values, int rows, int cols) { return cv::Mat(rows, cols, CV_64F, const_cast<double*>(values)).clone(); }

// camera_info against the dataset's opencv.yaml of the camera: the same K and D (and ξ first in
// D for the mirror camera), number for number.
void expectIntrinsicsOfTheFile(const sensor_msgs::CameraInfo& info, const fs::path& yaml) {
  cv::FileStorage file(yaml.string(), cv::FileStorage::READ);
  ASSERT_TRUE(file.isOpened()) << yaml;
  const cv::Mat k = file["K"].mat(), d = file["D"].mat();
  EXPECT_EQ(cv::norm(matrixOf(info.K.data(), 3, 3), k, cv::NORM_INF), 0.0);
  EXPECT_EQ(info.width, static_cast<uint32_t>(static_cast<int>(file["image_width"])));
  EXPECT_EQ(info.height, static_cast<uint32_t>(static_cast<int>(file["image_height"])));
  std::vector<double> expected;
  if (static_cast<std::string>(file["camera_model"]) == "omnidir") {
    EXPECT_EQ(info.distortion_model, "omnidirectional");
    expected.push_back(static_cast<double>(file["xi"]));
  } else {
    EXPECT_EQ(info.distortion_model, "equidistant");
  }
  expected.insert(expected.end(), d.begin<double>(), d.end<double>());
  EXPECT_EQ(info.D, expected);
}

// An equidistant camera_info as image_geometry reads it: undistorting cv::fisheye's projection
// of a point gives the point's pinhole projection.
void expectImageGeometryUndistortsCvFisheye(const sensor_msgs::CameraInfo& info) {
  image_geometry::PinholeCameraModel model;
  ASSERT_TRUE(model.fromCameraInfo(info));
  const cv::Matx33d k(info.K.data());
  const cv::Vec4d d(info.D[0], info.D[1], info.D[2], info.D[3]);
  for (const cv::Point3d point : {cv::Point3d(0.2, -0.1, 1.0), cv::Point3d(-0.6, 0.3, 1.0), cv::Point3d(0.9, 0.7, 1.0)}) {
    std::vector<cv::Point2d> raw;
    cv::fisheye::projectPoints(std::vector<cv::Point3d>{point}, raw, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, d);
    const cv::Point2d rectified = model.rectifyPoint(raw[0]), pinhole = model.project3dToPixel(point);
    EXPECT_NEAR(rectified.x, pinhole.x, 1e-3) << point;
    EXPECT_NEAR(rectified.y, pinhole.y, 1e-3) << point;
  }
}

// The messages of one topic as they arrive (on the spinner's thread), for the test's thread.
template <typename Message>
class Inbox {
 public:
  Inbox(ros::NodeHandle& handle, const std::string& topic)
      : subscriber_(handle.subscribe<Message>(topic, 100, [this](const typename Message::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex_);
          messages_.push_back(*m);
        })) {}
  size_t size() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_.size();
  }
  // A copy: the spinner may still add to the list.
  std::vector<Message> messages() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return messages_;
  }
  bool connected() const { return subscriber_.getNumPublishers() > 0; }

 private:
  mutable std::mutex mutex_;
  std::vector<Message> messages_;
  ros::Subscriber subscriber_;  // last: unsubscribed before the list goes
};
using Images = Inbox<sensor_msgs::Image>;

// The diagnostics' messages, one per status.
std::vector<std::string> diagnosticMessages(const Inbox<diagnostic_msgs::DiagnosticArray>& inbox) {
  std::vector<std::string> messages;
  for (const auto& array : inbox.messages())
    for (const auto& status : array.status) messages.push_back(status.message);
  return messages;
}

// One run against a master of the test's own: the spec's dataset rendered by the CLI, the program
// under test started with the master, and this process's node to talk to it.
class LiveRun : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    // roscpp initialises once per process: a second run in one process would wait for the first
    // one's master, gone. It fails at once instead, saying so.
    static int runsInThisProcess = 0;
    ASSERT_EQ(++runsInThisProcess, 1) << "roscpp initialises once per process: run one test of live_sensor_test per process "
                                      << "(ctest does), e.g. --gtest_filter=" << test->test_suite_name() << "." << test->name();
    root_ = fs::temp_directory_path() / ("omnicam_" + std::string(test->name()) + "_" + std::to_string(::getpid()));
    fs::create_directories(root_);
  }
  void TearDown() override {
    if (spinner_) spinner_->stop();
    program_.stop("program");  // then the master: neither writes into the folder any more
    master_.reset();
    fs::remove_all(root_);
  }

  // Writes the spec and renders its dataset with the CLI (into root/dataset).
  void renderDataset(const std::string& spec) {
    std::ofstream(root_ / "spec.json") << spec;
    const CommandResult dataset = runShell(std::string(OMNICAM_BINARY) + " dataset " + (root_ / "spec.json").string() +
                                           " -o " + (root_ / "dataset").string() + " 2>&1");
    ASSERT_EQ(dataset.code, 0) << dataset.out;
  }
  // Starts the master, this process's node, then `argv` with the master (its output in
  // root/program.out). With `simulatedTime`, /use_sim_time is set for the program (not for this
  // process's node, started before): its time is the /clock this test publishes.
  void start(const std::vector<std::string>& argv, const std::vector<std::string>& extraEnvironment = {},
             bool simulatedTime = false) {
    master_ = std::make_unique<RosMaster>(root_);
    ASSERT_EQ(master_->problem(), "");
    startRos(*master_);
    handle_ = std::make_unique<ros::NodeHandle>();
    spinner_ = std::make_unique<ros::AsyncSpinner>(1);
    spinner_->start();
    if (simulatedTime) ros::param::set("/use_sim_time", true);
    std::vector<std::string> environment = master_->environment();
    environment.insert(environment.end(), extraEnvironment.begin(), extraEnvironment.end());
    ASSERT_TRUE(program_.start("program", argv, root_ / "program.out", environment));
  }
  // Until `connected` holds: a message published before its connection would be lost.
  void waitUntilConnected(const std::function<bool()>& connected) {
    ASSERT_TRUE(TestDaemons::waitFor(connected, 120.0)) << output();
  }
  int waitForExit() { return program_.waitForExit("program", 120.0); }
  void stopProgram(int signal) { ::kill(program_.pid("program"), signal); }
  std::string output() const { return readFile(root_ / "program.out"); }
  fs::path dataset() const { return root_ / "dataset"; }

  fs::path root_;
  std::unique_ptr<RosMaster> master_;
  TestDaemons program_;
  std::unique_ptr<ros::NodeHandle> handle_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
};

nav_msgs::Odometry odometryOf(const SentPose& pose, ros::Time stamp, bool moving) {
  nav_msgs::Odometry m;
  m.header.stamp = stamp;
  m.header.frame_id = "odom";
  m.child_frame_id = "base_link";
  m.pose.pose.position.x = pose.x, m.pose.pose.position.y = pose.y;
  m.pose.pose.orientation.z = pose.qz, m.pose.pose.orientation.w = pose.qw;
  if (moving) m.twist.twist.linear.x = kForward, m.twist.twist.angular.z = kYawRateRadPerS;
  return m;
}

// `child` in `parent` at `stamp`: at (x, y), turned by the quaternion (0, 0, qz, qw).
geometry_msgs::TransformStamped transformAt(const char* parent, const char* child, ros::Time stamp, double x, double y = 0,
                                            double qz = 0, double qw = 1) {
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = x, t.transform.translation.y = y;
  t.transform.rotation.z = qz, t.transform.rotation.w = qw;
  return t;
}

void publishTransforms(const ros::Publisher& tf, std::vector<geometry_msgs::TransformStamped> transforms) {
  tf2_msgs::TFMessage m;
  m.transforms = std::move(transforms);
  tf.publish(m);
}

// Simulated time for the node under test (/use_sim_time): the test's /clock.
void publishClock(const ros::Publisher& clock, ros::Time now) {
  rosgraph_msgs::Clock m;
  m.clock = now;
  clock.publish(m);
}

// Every camera's frame, planes and camera_info of one pose, as the node published them.
struct CameraInboxes {
  std::map<std::string, std::unique_ptr<Images>> images;  // by leaf
  std::unique_ptr<Inbox<sensor_msgs::CameraInfo>> info;
};

TEST_F(LiveRun, RendersEveryOdometryPoseAsTheDatasetDoesForThreeCameras) {
  renderDataset(specText());
  start({OMNICAM_BINARY, "ros", (root_ / "spec.json").string(), "--robot", "bot", "--odom", "/bot/odom", "--frames",
         std::to_string(kPoses.size()), "--record", (root_ / "run.bag").string()});
  ros::Publisher odometry = handle_->advertise<nav_msgs::Odometry>("/bot/odom", 10);
  std::map<std::string, CameraInboxes> cameras;
  for (const std::string camera : kCameras) {
    for (const std::string leaf : kImageLeaves) cameras[camera].images[leaf] = std::make_unique<Images>(*handle_, "/bot/" + camera + "/" + leaf);
    cameras[camera].info = std::make_unique<Inbox<sensor_msgs::CameraInfo>>(*handle_, "/bot/" + camera + "/camera_info");
  }
  Inbox<tf2_msgs::TFMessage> mounts(*handle_, "/tf_static");
  Inbox<diagnostic_msgs::DiagnosticArray> diagnostics(*handle_, "/diagnostics");
  // Poses whose every message is in: each camera's planes and camera_info, and the mounts.
  const auto complete = [&] {
    size_t least = mounts.size() > 0 ? SIZE_MAX : 0;
    for (const auto& [camera, inboxes] : cameras) {
      least = std::min(least, inboxes.info->size());
      for (const auto& [leaf, images] : inboxes.images) least = std::min(least, images->size());
    }
    return least;
  };
  waitUntilConnected([&] {
    bool connected = odometry.getNumSubscribers() > 0 && mounts.connected() && diagnostics.connected();
    for (const auto& [camera, inboxes] : cameras) {
      connected = connected && inboxes.info->connected();
      for (const auto& [leaf, images] : inboxes.images) connected = connected && images->connected();
    }
    return connected;
  });

  // One pose at a time, each sent once the last one's images are in: nothing is dropped. After
  // the first, two hostile ones: each refused with a diagnostic, and the node goes on.
  for (size_t k = 0; k < kPoses.size(); ++k) {
    odometry.publish(odometryOf(kPoses[k], ros::Time(100 + static_cast<uint32_t>(k), 250), true));
    ASSERT_TRUE(TestDaemons::waitFor([&] { return complete() > k; }, 300.0)) << "pose " << k << ": " << output();
    if (k > 0) continue;
    nav_msgs::Odometry notFinite = odometryOf(kPoses[1], ros::Time(150, 0), true);
    notFinite.pose.pose.position.x = std::nan("");
    odometry.publish(notFinite);
    ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics.size() > 0; }, 120.0)) << output();
    odometry.publish(odometryOf(kPoses[1], ros::Time(99, 250), true));  // before pose 0's stamp
    ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics.size() > 1; }, 120.0)) << output();
    const std::vector<std::string> refused = diagnosticMessages(diagnostics);
    EXPECT_EQ(refused[0], "pose refused: a number of the pose or twist is not finite");
    EXPECT_EQ(refused[1], "pose refused: its stamp 99.000000250 is not after the last pose's, 100.000000250");
  }
  ASSERT_EQ(waitForExit(), 0) << output();
  EXPECT_NE(output().find(std::to_string(kPoses.size()) + " poses rendered, 0 dropped for newer ones, 2 refused"),
            std::string::npos)
      << output();

  std::map<std::string, std::vector<sensor_msgs::Image>> planes;  // by "camera/leaf", for expectPlanesOfTheFiles
  for (const std::string camera : kCameras) {
    for (const std::string leaf : kImageLeaves) planes[camera + "/" + leaf] = cameras[camera].images[leaf]->messages();
    const std::vector<sensor_msgs::CameraInfo> infos = cameras[camera].info->messages();
    for (size_t k = 0; k < kPoses.size(); ++k) {
      const sensor_msgs::Image& image = planes[camera + "/image_raw"][k];
      SCOPED_TRACE(camera + " pose " + std::to_string(k));
      EXPECT_EQ(image.header.stamp, ros::Time(100 + static_cast<uint32_t>(k), 250));
      EXPECT_EQ(image.header.frame_id, "bot/" + camera);
      EXPECT_EQ(image.encoding, "rgb8");
      EXPECT_EQ(image.step, image.width * 3);
      EXPECT_TRUE(image.data == datasetRgb8(dataset(), camera, static_cast<int>(k)));
      EXPECT_EQ(infos[k].header.stamp, image.header.stamp);
      EXPECT_EQ(infos[k].header.frame_id, "bot/" + camera);
      EXPECT_EQ(infos[k].width, image.width);
      EXPECT_EQ(infos[k].height, image.height);
      expectIntrinsicsOfTheFile(infos[k], dataset() / camera / "intrinsics" / "opencv.yaml");
      expectPlanesOfTheFiles(planes, camera, static_cast<int>(k), dataset());
    }
  }
  EXPECT_EQ(planes["front/image_raw"][0].width, 96u);
  expectImageGeometryUndistortsCvFisheye(cameras["fisheye"].info->messages()[0]);
  const std::vector<tf2_msgs::TFMessage> statics = mounts.messages();
  ASSERT_EQ(statics.size(), 1u);
  ASSERT_EQ(statics[0].transforms.size(), std::size(kCameras));
  for (const geometry_msgs::TransformStamped& mount : statics[0].transforms)
    expectMountOfTheTumPoses(mount, dataset() / mount.child_frame_id.substr(4) / "poses.tum");
  expectTheBagHoldsTheDataset(root_ / "run.bag", dataset());
  for (const fs::directory_entry& entry : fs::directory_iterator(root_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

// Poses from tf through a tree (map -> odom -> base_link), each image equal to the dataset's
// frame; a gap in the tree refuses its pose with a diagnostic, and the node goes on.
TEST_F(LiveRun, TakesPosesFromTfAndRefusesAGapInTheTree) {
  renderDataset(std::string(R"({"format": "omnicam-dataset/1", "scene": ")") + OMNICAM_SOURCE_DIR +
                R"(/scenes/robocup2006.json", "size": 96, "spp": 4, "shading": "lit", )" + poseList(kPoses.size()) +
                R"(, "cameras": [{"name": "front", "mount": {"x": 0.1, "y": 0, "yaw_deg": 0}}],
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  start({OMNICAM_BINARY, "ros", (root_ / "spec.json").string(), "--robot", "tfbot", "--tf", "map", "--frames",
         std::to_string(kPoses.size())});
  ros::Publisher tf = handle_->advertise<tf2_msgs::TFMessage>("/tf", 10);
  Images images(*handle_, "/tfbot/front/image_raw");
  Inbox<diagnostic_msgs::DiagnosticArray> diagnostics(*handle_, "/diagnostics");
  // The node's listener and its trigger share the node's one connection to /tf.
  waitUntilConnected([&] { return tf.getNumSubscribers() > 0 && images.connected() && diagnostics.connected(); });
  // First a gap: the robot moves in odom at 98 s and 99 s while map -> odom is not known yet.
  // The pose at 98 s waits until /tf data is 1 s past it, then is refused with tf's reason.
  publishTransforms(tf, {transformAt("odom", "base_link", ros::Time(98, 0), 1.5, 1.0, 1, 0)});
  publishTransforms(tf, {transformAt("odom", "base_link", ros::Time(99, 0), 1.5, 1.0, 1, 0)});
  ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics.size() > 0; }, 120.0)) << output();
  EXPECT_NE(diagnosticMessages(diagnostics)[0].find("pose refused: no transform from map to base_link: "), std::string::npos)
      << diagnosticMessages(diagnostics)[0];
  // map -> odom is 0.5 m along x at every stamp; odom -> base_link puts the robot at the spec's
  // poses. One at a time: each sent once the last one's image is in. The first one refuses the
  // pose at 99 s, still waiting: poses only go forward.
  for (size_t k = 0; k < kPoses.size(); ++k) {
    const ros::Time stamp(100 + static_cast<uint32_t>(k), 0);
    publishTransforms(tf, {transformAt("map", "odom", stamp, 0.5, 0, 0, 1),
                            transformAt("odom", "base_link", stamp, kPoses[k].x - 0.5, kPoses[k].y, kPoses[k].qz, kPoses[k].qw)});
    ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() > k; }, 120.0)) << "pose " << k << output();
  }
  ASSERT_EQ(waitForExit(), 0) << output();
  EXPECT_NE(output().find(std::to_string(kPoses.size()) + " poses rendered, 0 dropped for newer ones, 2 refused"),
            std::string::npos)
      << output();
  ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics.size() > 1; }, 120.0)) << output();
  const std::string overtaken = diagnosticMessages(diagnostics)[1];
  EXPECT_NE(overtaken.find("pose refused: no transform from map to base_link: "), std::string::npos) << overtaken;
  EXPECT_NE(overtaken.find("extrapolation at time 99.0"), std::string::npos) << overtaken;  // map -> odom is at 100 s only
  const std::vector<sensor_msgs::Image> frames = images.messages();
  for (size_t k = 0; k < kPoses.size(); ++k) {
    EXPECT_EQ(frames[k].header.stamp, ros::Time(100 + static_cast<uint32_t>(k), 0));
    EXPECT_TRUE(frames[k].data == datasetRgb8(dataset(), "front", static_cast<int>(k))) << "pose " << k;
  }
}

// A /tf stamp at the very end of ROS time made tf2's own arithmetic throw, which on the spinner
// thread ended the process (roscpp lets a callback's exception through to std::terminate); one
// merely far ahead was kept by tf2, which then dropped every later transform of the frame. Such a
// transform is not given to tf2: the pose is refused with the reason, and the next one renders.
TEST_F(LiveRun, OutlivesATfStampAtTheEndOfRosTime) {
  std::ofstream(root_ / "spec.json") << specText();
  start({OMNICAM_BINARY, "ros", (root_ / "spec.json").string(), "--robot", "tfbot", "--tf", "map", "--frames", "1"});
  ros::Publisher tf = handle_->advertise<tf2_msgs::TFMessage>("/tf", 10);
  Images images(*handle_, "/tfbot/front/image_raw");
  Inbox<diagnostic_msgs::DiagnosticArray> diagnostics(*handle_, "/diagnostics");
  waitUntilConnected([&] { return tf.getNumSubscribers() > 0 && images.connected() && diagnostics.connected(); });
  publishTransforms(tf, {transformAt("map", "base_link", ros::Time(4294967295u, 999999999u), 0, 0, 0, 1)});
  ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics.size() > 0; }, 120.0)) << output();
  EXPECT_NE(diagnosticMessages(diagnostics)[0].find("pose refused: no transform from map to base_link: the transform to base_link "
                                                    "is left out: the transform's stamp 4294967295.999999999 is more than 60 s "
                                                    "after ROS time now, "),
            std::string::npos)
      << diagnosticMessages(diagnostics)[0];
  // tf2 never kept it: the next transform, at ROS time now, is the robot's pose.
  publishTransforms(tf, {transformAt("map", "base_link", ros::Time::now(), 0.5, 0, 0, 1)});
  ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() > 0; }, 120.0)) << output();
  ASSERT_EQ(waitForExit(), 0) << output();
  EXPECT_NE(output().find("ros: 1 pose rendered, 0 dropped for newer ones, 1 refused"), std::string::npos) << output();
}

// A spec of one front camera with a rolling shutter (so a twist shows), poses `poses` ([x, y,
// yaw°] each), the robot driving forward at kForward m/s when `moving`.
std::string forwardSpec(const std::string& poses, bool moving) {
  return std::string(R"({"format": "omnicam-dataset/1", "scene": ")") + OMNICAM_SOURCE_DIR +
         R"(/scenes/robocup2006.json", "size": 96, "spp": 4, "shading": "lit", "poses": {"list": [)" + poses + "]}" +
         (moving ? R"(, "motion": {"velocity": [)" + std::to_string(kForward) + R"(, 0, 0]})" : std::string()) + R"(,
    "cameras": [{"name": "front", "mount": {"x": 0.1, "y": 0, "yaw_deg": 0}, "rig": )" + rollingShutterRig() + R"(}],
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})";
}

// A node on simulated time rendering at 4 Hz from odometry: the test sends the poses and moves
// /clock.
class SimulatedTimeRun : public LiveRun {
 protected:
  void startAtFourHertz(int frames) {
    start({OMNICAM_BINARY, "ros", (root_ / "spec.json").string(), "--robot", "bot", "--odom", "/bot/odom", "--rate", "4",
           "--frames", std::to_string(frames)},
          {}, /*simulatedTime=*/true);
    odometry_ = handle_->advertise<nav_msgs::Odometry>("/bot/odom", 10);
    clock_ = handle_->advertise<rosgraph_msgs::Clock>("/clock", 10);
    images_ = std::make_unique<Images>(*handle_, "/bot/front/image_raw");
    diagnostics_ = std::make_unique<Inbox<diagnostic_msgs::DiagnosticArray>>(*handle_, "/diagnostics");
    waitUntilConnected([&] {
      return odometry_.getNumSubscribers() > 0 && clock_.getNumSubscribers() > 0 && images_->connected() &&
             diagnostics_->connected();
    });
  }
  // A pose driving forward at kForward, then the same again: the second's refusal (its stamp is
  // not after the last) says the node has the first before the clock moves (odometry and /clock
  // come on two connections).
  void sendPose(const SentPose& pose, ros::Time stamp) {
    nav_msgs::Odometry m = odometryOf(pose, stamp, /*moving=*/false);
    m.twist.twist.linear.x = kForward;
    const size_t before = diagnostics_->size();
    odometry_.publish(m);
    odometry_.publish(m);
    ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics_->size() > before; }, 120.0)) << output();
  }
  void clockTo(ros::Time now) { publishClock(clock_, now); }
  void waitForImages(size_t count) {
    ASSERT_TRUE(TestDaemons::waitFor([&] { return images_->size() >= count; }, 120.0)) << output();
  }
  void waitForDiagnostics(size_t count) {
    ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics_->size() >= count; }, 120.0)) << output();
  }

  ros::Publisher odometry_, clock_;
  std::unique_ptr<Images> images_;
  std::unique_ptr<Inbox<diagnostic_msgs::DiagnosticArray>> diagnostics_;
};

// Each tick renders the newest odometry pose carried to the tick with its twist (a straight
// drive: x grows by kForward · Δt, exact in binary here), stamped with the tick; a tick too far
// from the newest pose is refused.
TEST_F(SimulatedTimeRun, RendersAtAFixedRateTheNewestPoseCarriedToEachTick) {
  // kPoses[0] = (-2, -1, 0°) carried 0 s and 0.25 s; kPoses[2] = (-1.5, 0, 0°) carried 0.25 s.
  renderDataset(forwardSpec("[-2, -1, 0], [-1.875, -1, 0], [-1.375, 0, 0]", /*moving=*/true));
  startAtFourHertz(3);
  sendPose(kPoses[0], ros::Time(100, 0));
  clockTo(ros::Time(100, 0));  // the tick at 100 s: the pose as it is
  waitForImages(1);
  clockTo(ros::Time(100, 300000000));  // the tick at 100.25 s: the pose 0.25 s on
  waitForImages(2);
  clockTo(ros::Time(101, 0));  // 1 s after the newest pose: refused
  waitForDiagnostics(2);
  sendPose(kPoses[2], ros::Time(101, 0));
  clockTo(ros::Time(101, 250000000));
  ASSERT_EQ(waitForExit(), 0) << output();
  waitForImages(3);

  const std::vector<sensor_msgs::Image> frames = images_->messages();
  const ros::Time ticks[] = {ros::Time(100, 0), ros::Time(100, 250000000), ros::Time(101, 250000000)};
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(frames[k].header.stamp, ticks[k]) << "tick " << k;
    EXPECT_TRUE(frames[k].data == datasetRgb8(dataset(), "front", static_cast<int>(k))) << "tick " << k;
  }
  const std::vector<std::string> messages = diagnosticMessages(*diagnostics_);
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_EQ(messages[1],
            "tick skipped: the newest pose, at 100.000000000, is 1.000 s from the tick at 101.000000000 (more than 0.5 s)");
  // Ticks are not poses: counted apart from the two poses refused (each sent twice: the second's
  // stamp is not after the first's).
  EXPECT_NE(output().find("3 frames rendered at ticks, 0 dropped for newer ones, 2 refused, 0 new masters, 1 tick skipped (no pose "
                          "within --max-pose-age)\n"),
            std::string::npos) << output();
}

// A simulation reset sends /clock back: the node ticks again from there and takes the new run's
// poses, though their stamps are before the old run's (said once on /diagnostics).
TEST_F(SimulatedTimeRun, StartsAnewWhenSimulatedTimeGoesBack) {
  renderDataset(forwardSpec("[-2, -1, 0], [-1.375, 0, 0]", /*moving=*/true));
  startAtFourHertz(2);
  sendPose(kPoses[0], ros::Time(100, 0));
  clockTo(ros::Time(100, 0));
  waitForImages(1);
  clockTo(ros::Time(50, 0));  // the reset: its first tick says so
  waitForDiagnostics(2);
  sendPose(kPoses[2], ros::Time(50, 0));  // before 100 s, taken all the same
  clockTo(ros::Time(50, 250000000));
  ASSERT_EQ(waitForExit(), 0) << output();
  waitForImages(2);
  const std::vector<sensor_msgs::Image> frames = images_->messages();
  EXPECT_EQ(frames[0].header.stamp, ros::Time(100, 0));
  EXPECT_EQ(frames[1].header.stamp, ros::Time(50, 250000000));
  for (int k = 0; k < 2; ++k) EXPECT_TRUE(frames[k].data == datasetRgb8(dataset(), "front", k)) << "frame " << k;
  EXPECT_EQ(diagnosticMessages(*diagnostics_)[1], "ROS time went back (a simulation reset?): poses start anew");
}

// At a fixed rate from tf: each tick asks the tree for the robot at the tick and renders it once
// tf reaches it (tf2 interpolates between its data), stamped with the tick. Started by roslaunch
// with the launch file's tf, rate, frames and record arguments; the bag holds the frames.
TEST_F(LiveRun, RendersAtAFixedRateTheTreesPoseAtEachTick) {
  renderDataset(forwardSpec("[0.5, 0, 0], [1, 0, 0], [1.5, 0, 0]", /*moving=*/false));  // tf has no twist
  start({"/usr/bin/roslaunch", "omnicam", "live_camera.launch", "spec:=" + (root_ / "spec.json").string(), "robot:=bot",
         "tf:=map", "rate:=4", "frames:=3", "record:=" + (root_ / "ticks.bag").string()},
        {"ROS_PACKAGE_PATH=" OMNICAM_ROS_PACKAGE_PATH}, /*simulatedTime=*/true);
  ros::Publisher tf = handle_->advertise<tf2_msgs::TFMessage>("/tf", 10);
  ros::Publisher clock = handle_->advertise<rosgraph_msgs::Clock>("/clock", 10);
  Images images(*handle_, "/bot/front/image_raw");
  waitUntilConnected([&] { return tf.getNumSubscribers() > 0 && clock.getNumSubscribers() > 0 && images.connected(); });
  const auto robotAt = [&](ros::Time stamp, double x) { publishTransforms(tf, {transformAt("map", "base_link", stamp, x)}); };
  const auto clockTo = [&](ros::Time now) { publishClock(clock, now); };
  robotAt(ros::Time(100, 0), 0.0);
  robotAt(ros::Time(100, 500000000), 1.0);
  clockTo(ros::Time(100, 250000000));  // between two of the tree's poses: x 0.5
  ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() >= 1; }, 120.0)) << output();
  clockTo(ros::Time(100, 500000000));  // at one: x 1
  ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() >= 2; }, 120.0)) << output();
  clockTo(ros::Time(100, 750000000));  // beyond the tree's newest (if it comes first): the tick waits for tf
  robotAt(ros::Time(101, 0), 2.0);     // x 1.5 at the tick
  ASSERT_EQ(waitForExit(), 0) << output();
  const std::vector<sensor_msgs::Image> frames = images.messages();
  ASSERT_EQ(frames.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(frames[k].header.stamp, ros::Time(100, 250000000 * static_cast<uint32_t>(k + 1))) << "tick " << k;
    EXPECT_TRUE(frames[k].data == datasetRgb8(dataset(), "front", static_cast<int>(k))) << "tick " << k;
  }
  EXPECT_NE(output().find("3 frames rendered at ticks, 0 dropped for newer ones, 0 refused"), std::string::npos) << output();
  rosbag::Bag bag((root_ / "ticks.bag").string(), rosbag::bagmode::Read);
  std::vector<sensor_msgs::Image> recorded;
  for (const rosbag::MessageInstance& m : rosbag::View(bag, rosbag::TopicQuery("/bot/front/image_raw")))
    recorded.push_back(*m.instantiate<sensor_msgs::Image>());
  ASSERT_EQ(recorded.size(), 3u);
  for (size_t k = 0; k < 3; ++k) EXPECT_TRUE(recorded[k].data == frames[k].data) << "tick " << k;
}

// At a fixed rate from tf, started before the robot's tree: the ticks before its first pose are
// no poses (as before the first odometry). They are said once on /diagnostics, not refused at the
// rate, and the first tick the tree reaches renders as usual.
TEST_F(LiveRun, TicksBeforeTheTreesFirstPoseAreSaidOnceNotRefused) {
  renderDataset(forwardSpec("[0.5, 0, 0]", /*moving=*/false));
  start({OMNICAM_BINARY, "ros", (root_ / "spec.json").string(), "--robot", "bot", "--tf", "map", "--rate", "4", "--frames",
         "1"},
        {}, /*simulatedTime=*/true);
  ros::Publisher tf = handle_->advertise<tf2_msgs::TFMessage>("/tf", 10);
  ros::Publisher clock = handle_->advertise<rosgraph_msgs::Clock>("/clock", 10);
  Images images(*handle_, "/bot/front/image_raw");
  Inbox<diagnostic_msgs::DiagnosticArray> diagnostics(*handle_, "/diagnostics");
  waitUntilConnected([&] { return tf.getNumSubscribers() > 0 && clock.getNumSubscribers() > 0 && images.connected() && diagnostics.connected(); });
  // Time passes with no tree: the clock steps a tick at a time until the node says why it waits
  // (a tick expires 1 s after its stamp; the node sees whichever clock values it sees).
  ros::Time now(100, 0);
  for (int step = 0; diagnostics.size() == 0; ++step) {
    ASSERT_LT(step, 2000) << output();
    publishClock(clock, now);
    TestDaemons::waitFor([&] { return diagnostics.size() > 0; }, 0.05);
    now += ros::Duration(0.25);
  }
  const std::string waiting = diagnosticMessages(diagnostics)[0];
  EXPECT_EQ(waiting.rfind("waiting for the tree's first pose (said once): no transform from map to base_link: ", 0), 0u) << waiting;
  // The robot at x 0.5 from now on: the next tick renders it.
  publishTransforms(tf, {transformAt("map", "base_link", now - ros::Duration(1.0), 0.5),
                         transformAt("map", "base_link", now + ros::Duration(5.0), 0.5)});
  publishClock(clock, now);
  ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() > 0; }, 120.0)) << output();
  ASSERT_EQ(waitForExit(), 0) << output();
  ASSERT_EQ(images.size(), 1u);
  EXPECT_TRUE(images.messages()[0].data == datasetRgb8(dataset(), "front", 0));
  // (Ticks that waited within tf's patience and that the tree then reached are poses: the newest
  // of them rendered, the others dropped for it.)
  EXPECT_NE(output().find("ros: 1 frame rendered at ticks, "), std::string::npos) << output();
  EXPECT_NE(output().find(" dropped for newer ones, 0 refused, 0 new masters"), std::string::npos) << output();
  for (const std::string& message : diagnosticMessages(diagnostics))
    EXPECT_EQ(message.find("pose refused"), std::string::npos) << message;
}

// The pid of ROS node `name` (its getPid, found through the master), 0 if it does not answer.
int nodePid(const std::string& name) {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = name;
  if (!ros::master::execute("lookupNode", args, result, payload, false)) return 0;
  std::string host;
  uint32_t port = 0;
  if (!ros::network::splitURI(static_cast<std::string>(payload), host, port)) return 0;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue request, reply;
  request[0] = ros::this_node::getName();
  if (!client.execute("getPid", request, reply) || reply.getType() != XmlRpc::XmlRpcValue::TypeArray || reply.size() != 3)
    return 0;
  return static_cast<int>(reply[2]);
}

// roslaunch starts the node from the build folder's ROS package (ROS_PACKAGE_PATH), its launch
// file included by a user's with a remapping and a node name; its images equal the dataset's
// frames; Ctrl-C to roslaunch ends the node cleanly, and nothing is left running.
TEST_F(LiveRun, StartsFromItsLaunchFileAndEndsWithRoslaunch) {
  renderDataset(forwardSpec("[-2, -1, 0], [-1.75, -0.5, 180]", /*moving=*/true));
  // A user's launch file: ours included after a remapping of the camera's image.
  std::ofstream(root_ / "hall.launch") << R"(<launch>
  <remap from="/bot/front/image_raw" to="/hall/image"/>
  <include file="$(find omnicam)/launch/live_camera.launch">
    <arg name="spec" value=")" << (root_ / "spec.json").string() << R"("/>
    <arg name="robot" value="bot"/>
    <arg name="odom" value="/bot/odom"/>
    <arg name="node_name" value="hall_camera"/>
  </include>
</launch>
)";
  start({"/usr/bin/roslaunch", (root_ / "hall.launch").string()}, {"ROS_PACKAGE_PATH=" OMNICAM_ROS_PACKAGE_PATH});
  ros::Publisher odometry = handle_->advertise<nav_msgs::Odometry>("/bot/odom", 10);
  Images images(*handle_, "/hall/image");  // remapped
  waitUntilConnected([&] { return odometry.getNumSubscribers() > 0 && images.connected(); });
  const int node = nodePid("/hall_camera");
  ASSERT_GT(node, 0) << output();
  for (size_t k = 0; k < 2; ++k) {
    nav_msgs::Odometry m = odometryOf(kPoses[k], ros::Time(100 + static_cast<uint32_t>(k), 0), /*moving=*/false);
    m.twist.twist.linear.x = kForward;
    odometry.publish(m);
    ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() > k; }, 120.0)) << output();
  }
  stopProgram(SIGINT);
  EXPECT_EQ(waitForExit(), 0) << output();
  // The ready line names the topics as remapped: where a user listens.
  EXPECT_NE(output().find("ros: ready: poses from /bot/odom, images on /hall/image\n"), std::string::npos) << output();
  EXPECT_NE(output().find("ros: 2 poses rendered, 0 dropped for newer ones, 0 refused"), std::string::npos) << output();
  EXPECT_NE(::kill(node, 0), 0) << "the node " << node << " outlived roslaunch";
  const std::vector<sensor_msgs::Image> frames = images.messages();
  for (int k = 0; k < 2; ++k) EXPECT_TRUE(frames[k].data == datasetRgb8(dataset(), "front", k)) << "pose " << k;
}

// roslaunch starts the node in ROS_HOME: a relative spec:= would be looked for there, not where
// roslaunch was started. The node (knowing roslaunch by its __log:=) refuses it on one line that
// says where it runs and how to give the path.
TEST_F(LiveRun, ARelativeSpecUnderRoslaunchIsRefusedSayingWhereTheNodeRuns) {
  renderDataset(specText());
  start({"/usr/bin/roslaunch", "omnicam", "live_camera.launch", "spec:=spec.json", "robot:=bot"},
        {"ROS_PACKAGE_PATH=" OMNICAM_ROS_PACKAGE_PATH});
  EXPECT_NE(waitForExit(), -1) << "roslaunch ends with its required node: " << output();
  std::string home;
  for (const std::string& variable : master_->environment())
    if (variable.rfind("ROS_HOME=", 0) == 0) home = fs::canonical(variable.substr(std::string("ROS_HOME=").size())).string();
  EXPECT_NE(output().find("omnicam: ros: spec.json is a relative path, but roslaunch starts its nodes in " + home +
                          ", not where it was started: give an absolute path (spec:=$PWD/spec.json)\n"),
            std::string::npos)
      << output();
  EXPECT_EQ(output().find("ros: ready"), std::string::npos) << output();
}

// A spec the dataset reader refuses is refused the same way, before any master is looked for.
TEST(LiveSensor, RefusesASpecAsTheDatasetReaderDoes) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_live_sensor_spec_" + std::to_string(::getpid()));
  fs::create_directories(root);
  std::string text = specText();
  const std::string spp = "\"spp\": 4";
  text.replace(text.find(spp), spp.size(), "\"spp\": 5");
  std::ofstream(root / "spec.json") << text;
  const std::string spec = (root / "spec.json").string();
  const CommandResult live = runShell(std::string(OMNICAM_BINARY) + " ros " + spec + " 2>&1");
  const CommandResult dataset = runShell(std::string(OMNICAM_BINARY) + " dataset " + spec + " -o " + (root / "d").string() + " 2>&1");
  EXPECT_EQ(live.code, 2) << live.out;
  EXPECT_EQ(dataset.code, 2) << dataset.out;
  EXPECT_NE(live.out.find("spp: must be a perfect square"), std::string::npos) << live.out;
  EXPECT_EQ(live.out, dataset.out);
  fs::remove_all(root);
}

// A master that goes away and comes back: the node keeps running, registers every topic with
// the new master (saying so on /diagnostics) and renders the next pose as before.
TEST_F(LiveRun, OutlivesItsMasterAndRegistersAgainWhenItComesBack) {
  renderDataset(specText());
  start({OMNICAM_BINARY, "ros", (root_ / "spec.json").string(), "--robot", "bot", "--odom", "/bot/odom", "--frames", "2"});
  std::optional<ros::Publisher> odometry = handle_->advertise<nav_msgs::Odometry>("/bot/odom", 10);
  auto images = std::make_unique<Images>(*handle_, "/bot/front/image_raw");
  waitUntilConnected([&] { return odometry->getNumSubscribers() > 0 && images->connected(); });
  odometry->publish(odometryOf(kPoses[0], ros::Time(100, 250), true));
  ASSERT_TRUE(TestDaemons::waitFor([&] { return images->size() > 0; }, 120.0)) << output();
  const sensor_msgs::Image first = images->messages()[0];

  master_->stop();
  master_->restart();
  ASSERT_EQ(master_->problem(), "");
  // This process's topics are new to the new master too.
  odometry.reset();
  images.reset();
  odometry = handle_->advertise<nav_msgs::Odometry>("/bot/odom", 10);
  images = std::make_unique<Images>(*handle_, "/bot/front/image_raw");
  // The cameras' mounts too: a tf listener that joins after the restart must get them (the
  // static broadcaster was made again before the old one went, and never registered).
  Inbox<tf2_msgs::TFMessage> mounts(*handle_, "/tf_static");
  waitUntilConnected([&] { return odometry->getNumSubscribers() > 0 && images->connected(); });
  ASSERT_TRUE(TestDaemons::waitFor([&] { return mounts.size() > 0; }, 120.0)) << "no /tf_static from the new master\n" << output();
  odometry->publish(odometryOf(kPoses[1], ros::Time(101, 250), true));
  ASSERT_TRUE(TestDaemons::waitFor([&] { return images->size() > 0; }, 120.0)) << output();
  ASSERT_EQ(waitForExit(), 0) << output();
  EXPECT_TRUE(first.data == datasetRgb8(dataset(), "front", 0));
  EXPECT_TRUE(images->messages()[0].data == datasetRgb8(dataset(), "front", 1));
  // (Its diagnostic goes out as the node registers again, before a subscriber can connect.)
  EXPECT_NE(output().find("2 poses rendered, 0 dropped for newer ones, 0 refused, 1 new master\n"), std::string::npos)
      << output();
}

// A pose the engine cannot render as a dataset frame (here a robot whose mount puts the camera
// beyond the world's ±10 km, then adaptive sampling while a rolling shutter moves) is refused with
// its reason; the next, still one renders as the dataset does.
TEST_F(LiveRun, RefusesAPoseItsEngineCannotRenderAndGoesOn) {
  renderDataset(std::string(R"({"format": "omnicam-dataset/1", "scene": ")") + OMNICAM_SOURCE_DIR +
                R"(/scenes/robocup2006.json", "size": 96, "spp": 4, "shading": "path", "adaptive_spp": 16, )" + poseList(1) +
                R"(, "cameras": [{"name": "front", "mount": {"x": 0.1, "y": 0, "yaw_deg": 0}, "rig": )" + rollingShutterRig() +
                R"(}], "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  start({OMNICAM_BINARY, "ros", (root_ / "spec.json").string(), "--robot", "bot", "--odom", "/bot/odom", "--frames", "1"});
  ros::Publisher odometry = handle_->advertise<nav_msgs::Odometry>("/bot/odom", 10);
  Images images(*handle_, "/bot/front/image_raw");
  Inbox<diagnostic_msgs::DiagnosticArray> diagnostics(*handle_, "/diagnostics");
  waitUntilConnected([&] { return odometry.getNumSubscribers() > 0 && images.connected() && diagnostics.connected(); });
  SentPose atTheEdge = kPoses[0];
  atTheEdge.x = 9999.95, atTheEdge.qz = 0.0, atTheEdge.qw = 1.0, atTheEdge.yawDeg = 0.0;  // within the world; its camera 0.1 m ahead is not
  odometry.publish(odometryOf(atTheEdge, ros::Time(99, 0), /*moving=*/false));
  ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics.size() > 0; }, 120.0)) << output();
  EXPECT_EQ(diagnosticMessages(diagnostics)[0].rfind("pose refused: the pose (camera \"front\"): the camera must stand within ±10000 m; "
                                                     "the robot at (9999.95, ",
                                                     0),
            0u)
      << diagnosticMessages(diagnostics)[0];
  odometry.publish(odometryOf(kPoses[0], ros::Time(100, 0), /*moving=*/true));
  ASSERT_TRUE(TestDaemons::waitFor([&] { return diagnostics.size() > 1; }, 120.0)) << output();
  EXPECT_EQ(diagnosticMessages(diagnostics)[1],
            "pose refused: adaptive_spp: not while the robot moves during an exposure (camera \"front\")");
  odometry.publish(odometryOf(kPoses[0], ros::Time(101, 0), /*moving=*/false));
  ASSERT_EQ(waitForExit(), 0) << output();
  ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() > 0; }, 120.0)) << output();
  EXPECT_TRUE(images.messages()[0].data == datasetRgb8(dataset(), "front", 0));
  EXPECT_NE(output().find("1 pose rendered, 0 dropped for newer ones, 2 refused"), std::string::npos) << output();
}

// A signal while POV-Ray renders a frame ends POV-Ray with its process group (base/interrupts.h):
// that frame is given up, and the node ends with exit code 0 and a finished bag of the frames
// before it (the bag was deleted with the frame). POV-Ray is a script that renders the first
// frame and holds the second until the signal: the test sends it once the script says it holds.
TEST_F(LiveRun, ASignalDuringAPovrayFrameGivesItUpAndKeepsTheBagOfTheFramesBefore) {
  std::ofstream(root_ / "spec.json") << std::string(R"({"format": "omnicam-dataset/1", "scene": ")") + OMNICAM_SOURCE_DIR +
                                            R"(/scenes/robocup2006.json", "engine": "povray", "size": 48, "spp": 1, "shading": "lit", )" +
                                            poseList(2) + R"(, "cameras": [{"name": "front", "mount": {"x": 0.1, "y": 0, "yaw_deg": 0}}],
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})";
  const fs::path povray = root_ / "povray", holding = root_ / "holding", hold = root_ / "hold";
  std::ofstream(povray) << "#!/bin/sh\nif [ -e '" << hold.string() << "' ]; then : > '" << holding.string()
                        << "'; exec sleep 600; fi\nexec povray \"$@\"\n";
  fs::permissions(povray, fs::perms::owner_all);
  const fs::path bag = root_ / "run.bag";
  start({OMNICAM_BINARY, "ros", (root_ / "spec.json").string(), "--robot", "bot", "--odom", "/bot/odom", "--record", bag.string()},
        {"OMNICAM_POVRAY=" + povray.string()});
  ros::Publisher odometry = handle_->advertise<nav_msgs::Odometry>("/bot/odom", 10);
  Images images(*handle_, "/bot/front/image_raw");
  waitUntilConnected([&] { return odometry.getNumSubscribers() > 0 && images.connected(); });
  odometry.publish(odometryOf(kPoses[0], ros::Time(100, 0), /*moving=*/false));
  ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() > 0; }, 120.0)) << output();
  std::ofstream(hold) << "";
  odometry.publish(odometryOf(kPoses[1], ros::Time(101, 0), /*moving=*/false));
  ASSERT_TRUE(TestDaemons::waitFor([&] { return fs::exists(holding); }, 120.0)) << output();
  stopProgram(SIGTERM);
  ASSERT_EQ(waitForExit(), 0) << output();
  EXPECT_NE(output().find("ros: interrupted by SIGTERM (povray ended): the frame in progress was given up; the bag holds the "
                          "frames before it\nros: 1 pose rendered, 0 dropped for newer ones, 0 refused"),
            std::string::npos)
      << output();
  ASSERT_TRUE(fs::exists(bag)) << output();
  rosbag::Bag recorded(bag.string(), rosbag::bagmode::Read);
  std::vector<sensor_msgs::Image> frames;
  for (const rosbag::MessageInstance& m : rosbag::View(recorded, rosbag::TopicQuery("/bot/front/image_raw")))
    if (const sensor_msgs::Image::ConstPtr image = m.instantiate<sensor_msgs::Image>()) frames.push_back(*image);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_TRUE(frames[0].data == images.messages()[0].data);
  for (const fs::directory_entry& entry : fs::directory_iterator(root_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

// examples/python/ros_camera.py: omnicam.Renderer behind a rospy callback, each image equal to
// the dataset's frame of the pose; SIGTERM ends it cleanly.
TEST_F(LiveRun, PythonExamplePublishesTheRenderersFramesForOdometryPoses) {
  const std::string scene = std::string(OMNICAM_SOURCE_DIR) + "/scenes/robocup2006.json";
  renderDataset(std::string(R"({"format": "omnicam-dataset/1", "scene": ")") + scene + R"(", "spp": 4, "shading": "lit", )" +
                poseList(2) + R"(,
    "outputs": {"rgb": "png", "depth": false, "instance": false, "semantic": false, "normal": false, "landmarks": false}})");
  start({"/usr/bin/python3", std::string(OMNICAM_SOURCE_DIR) + "/examples/python/ros_camera.py", scene, "--odom", "/py/odom",
         "--image", "/py/image_raw"},
        {"PYTHONPATH=" OMNICAM_PYTHON_DIR, "GLIBC_TUNABLES=glibc.cpu.hwcaps=-FMA,-FMA4"});  // the CLI's math (docs/python.md)
  ros::Publisher odometry = handle_->advertise<nav_msgs::Odometry>("/py/odom", 10);
  Images images(*handle_, "/py/image_raw");
  waitUntilConnected([&] { return odometry.getNumSubscribers() > 0 && images.connected(); });
  for (size_t k = 0; k < 2; ++k) {
    odometry.publish(odometryOf(kPoses[k], ros::Time(100 + static_cast<uint32_t>(k), 0), false));
    ASSERT_TRUE(TestDaemons::waitFor([&] { return images.size() > k; }, 120.0)) << output();
  }
  stopProgram(SIGTERM);
  EXPECT_EQ(waitForExit(), 0) << output();
  EXPECT_NE(output().find("ros_camera: 2 poses rendered"), std::string::npos) << output();
  const std::vector<sensor_msgs::Image> frames = images.messages();
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(frames[k].encoding, "rgb8");
    EXPECT_EQ(frames[k].header.stamp, ros::Time(100 + k, 0));
    EXPECT_TRUE(frames[k].data == datasetRgb8(dataset(), "cam0", k)) << "pose " << k;
  }
}

// Names a dataset takes but ROS does not (a camera "front-left", a robot "my bot"): one line,
// exit 2, before any master is looked for.
TEST(LiveSensor, RefusesNamesRosCannotTake) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_live_sensor_names_" + std::to_string(::getpid()));
  fs::create_directories(root);
  std::string text = specText();
  text.replace(text.find("\"front\""), 7, "\"front-left\"");
  std::ofstream(root / "camera.json") << text;
  std::ofstream(root / "spec.json") << specText();
  // Each names what the user gave: the spec's field, or the robot name.
  const std::pair<std::string, std::string> named[] = {
      {(root / "camera.json").string(), "ros: camera \"front-left\" (" + (root / "camera.json").string() + ": cameras[0].name): "},
      {(root / "spec.json").string() + " --robot 'my bot'", "ros: the robot name: \"/my bot\" is not a ROS name"}};
  for (const auto& [arguments, words] : named) {
    const CommandResult run = runShell(std::string(OMNICAM_BINARY) + " ros " + arguments + " 2>&1");
    EXPECT_EQ(run.code, 2) << run.out;
    EXPECT_NE(run.out.find("is not a ROS name"), std::string::npos) << run.out;
    EXPECT_NE(run.out.find(words), std::string::npos) << run.out;
    EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
  }
  // Frame ids tf2 refuses (tf1's leading '/'), empty names and values that would silently mean
  // the flag's absence: each would have every pose refused, or topics and frames without a robot.
  const std::pair<const char*, const char*> cases[] = {
      {"--tf /map", "ros: the poses' frame \"/map\": a tf2 frame id does not start with '/' (give \"map\")"},
      {"--base-frame /base_link", "ros: the robot's frame \"/base_link\": a tf2 frame id does not start with '/' (give \"base_link\")"},
      {"--base-frame ''", "ros: the robot's frame is empty"},
      {"--tf base_link", "ros: the poses' frame is the robot's frame itself (\"base_link\")"},
      {"--robot ''", "ros: robot name \"\": one name, without '/'"},
      {"--robot bot/sub", "ros: robot name \"bot/sub\": one name, without '/'"},
      {"--odom ''", "ros: the odometry topic is empty"},
      {"--tf ''", "--tf: give a frame (map or odom)"},
      {"--record ''", "--record: give the new bag's file name"}};
  for (const auto& [arguments, expected] : cases) {
    const CommandResult run = runShell(std::string(OMNICAM_BINARY) + " ros " + (root / "spec.json").string() + " " + arguments + " 2>&1");
    EXPECT_EQ(run.code, 2) << arguments << ": " << run.out;
    EXPECT_NE(run.out.find(expected), std::string::npos) << arguments << ": " << run.out;
    EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
  }
  fs::remove_all(root);
}

// Arguments other than ROS's own (from:=to), and a node name ROS refuses: one line, exit 2,
// before any master is looked for.
TEST(LiveSensor, RefusesArgumentsThatAreNotRosOnes) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_live_sensor_arguments_" + std::to_string(::getpid()));
  fs::create_directories(root);
  std::ofstream(root / "spec.json") << specText();
  const std::pair<const char*, const char*> cases[] = {{"stray", "unexpected argument \"stray\""},
                                                       {":=x", "unexpected argument \":=x\""},
                                                       {"__name:=front-left", "ros: \"__name:=front-left\": Character [-] at element [5]"},
                                                       {"__name:=", "ros: \"__name:=\": give a name, or leave __name:= out"},
                                                       {"__ns:=", "ros: \"__ns:=\": give a name, or leave __ns:= out"},
                                                       {"_rate:=30", "the node takes no private parameters"}};
  for (const auto& [argument, expected] : cases) {
    const CommandResult run = runShell(std::string(OMNICAM_BINARY) + " ros " + (root / "spec.json").string() + " '" + argument +
                                       "' 2>&1");
    EXPECT_EQ(run.code, 2) << argument << ": " << run.out;
    EXPECT_NE(run.out.find(expected), std::string::npos) << argument << ": " << run.out;
    EXPECT_EQ(std::count(run.out.begin(), run.out.end(), '\n'), 1) << run.out;
  }
  fs::remove_all(root);
}

// A bag is a new file: an existing one (or a link) is never overwritten, before any master is
// looked for.
TEST(LiveSensor, NeverOverwritesABag) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_live_sensor_bag_" + std::to_string(::getpid()));
  fs::create_directories(root);
  std::ofstream(root / "spec.json") << specText();
  std::ofstream(root / "old.bag") << "someone's bag";
  fs::create_symlink(root / "elsewhere.bag", root / "link.bag");
  for (const char* bag : {"old.bag", "link.bag"}) {
    const CommandResult run = runShell(std::string(OMNICAM_BINARY) + " ros " + (root / "spec.json").string() + " --record " +
                                       (root / bag).string() + " 2>&1");
    EXPECT_EQ(run.code, 2) << run.out;
    EXPECT_NE(run.out.find("--record: "), std::string::npos) << run.out;
    EXPECT_NE(run.out.find(std::string(bag) == "old.bag" ? "exists already" : "is a symbolic link"), std::string::npos) << run.out;
  }
  EXPECT_EQ(readFile(root / "old.bag"), "someone's bag");
  EXPECT_FALSE(fs::exists(root / "elsewhere.bag"));
  fs::remove_all(root);
}

// A live node runs until it is told to stop: SIGINT (Ctrl-C) or SIGTERM (roslaunch, systemd) end
// it cleanly between frames, exit code 0, with nothing left running.
class LiveSensorStops : public ::testing::TestWithParam<int> {};

TEST_P(LiveSensorStops, OnItsSignalWithExitCodeZero) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_live_sensor_stop_" + std::to_string(::getpid()));
  fs::create_directories(root);
  std::ofstream(root / "spec.json") << specText();
  RosMaster master(root);
  ASSERT_EQ(master.problem(), "");
  TestDaemons node;
  ASSERT_TRUE(node.start("omnicam ros", {OMNICAM_BINARY, "ros", (root / "spec.json").string()}, root / "node.out",
                         master.environment()));
  ASSERT_TRUE(TestDaemons::waitFor([&] { return readFile(root / "node.out").find("ros: ready") != std::string::npos; }, 120.0))
      << readFile(root / "node.out");
  // The ready line names the topics themselves (the default robot namespace).
  EXPECT_NE(readFile(root / "node.out").find("images on /robot/front/image_raw, /robot/rear/image_raw, /robot/fisheye/image_raw"),
            std::string::npos) << readFile(root / "node.out");
  ::kill(node.pid("omnicam ros"), GetParam());
  EXPECT_EQ(node.waitForExit("omnicam ros", 60.0), 0) << readFile(root / "node.out");
  EXPECT_NE(readFile(root / "node.out").find("ros: 0 poses rendered"), std::string::npos) << readFile(root / "node.out");
  fs::remove_all(root);
}

INSTANTIATE_TEST_SUITE_P(Signals, LiveSensorStops, ::testing::Values(SIGINT, SIGTERM));

// A second node under the first one's name: the master shuts the first down (roscpp's rule), which
// would then hear no pose and publish nothing. It says so and ends with exit code 3; the second
// runs on and stops on its signal.
TEST(LiveSensor, EndsWhenAnotherNodeTakesItsName) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_live_sensor_name_" + std::to_string(::getpid()));
  fs::create_directories(root);
  std::ofstream(root / "spec.json") << specText();
  RosMaster master(root);
  ASSERT_EQ(master.problem(), "");
  TestDaemons nodes;
  const auto ready = [&](const char* out) { return readFile(root / out).find("ros: ready") != std::string::npos; };
  ASSERT_TRUE(nodes.start("first", {OMNICAM_BINARY, "ros", (root / "spec.json").string(), "--record", (root / "first.bag").string()},
                          root / "first.out", master.environment()));
  ASSERT_TRUE(TestDaemons::waitFor([&] { return ready("first.out"); }, 120.0)) << readFile(root / "first.out");
  ASSERT_TRUE(nodes.start("second", {OMNICAM_BINARY, "ros", (root / "spec.json").string()}, root / "second.out", master.environment()));
  EXPECT_EQ(nodes.waitForExit("first", 120.0), 3) << readFile(root / "first.out");
  EXPECT_NE(readFile(root / "first.out").find("omnicam: ros: the ROS master shut this node down: another node registered under its name"),
            std::string::npos) << readFile(root / "first.out");
  EXPECT_TRUE(fs::exists(root / "first.bag")) << "the bag it recorded is kept: " << readFile(root / "first.out");
  ASSERT_TRUE(TestDaemons::waitFor([&] { return ready("second.out"); }, 120.0)) << readFile(root / "second.out");
  ::kill(nodes.pid("second"), SIGINT);
  EXPECT_EQ(nodes.waitForExit("second", 60.0), 0) << readFile(root / "second.out");
  fs::remove_all(root);
}

// With no master, the node says at once that it waits for one, and where; a signal then ends it
// with exit code 0, as it does once connected. The port is this test's, bound and never listened
// on: nothing answers there.
class LiveSensorWaitingForAMaster : public ::testing::TestWithParam<int> {};

TEST_P(LiveSensorWaitingForAMaster, SaysSoAndStopsOnItsSignalWithExitCodeZero) {
  const fs::path root = fs::temp_directory_path() / ("omnicam_live_sensor_nomaster_" + std::to_string(::getpid()));
  fs::create_directories(root);
  std::ofstream(root / "spec.json") << specText();
  const int port = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(port, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof address;
  ASSERT_EQ(::bind(port, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  ASSERT_EQ(::getsockname(port, reinterpret_cast<sockaddr*>(&address), &length), 0);
  const std::string uri = "http://127.0.0.1:" + std::to_string(ntohs(address.sin_port));
  TestDaemons node;
  ASSERT_TRUE(node.start("omnicam ros", {OMNICAM_BINARY, "ros", (root / "spec.json").string()}, root / "node.out",
                         {"ROS_MASTER_URI=" + uri, "ROS_HOME=" + (root / "ros_home").string(), "ROS_IP=127.0.0.1"}));
  const std::string waiting = "ros: waiting for a ROS master at " + uri + " (start one with `roscore`";
  ASSERT_TRUE(TestDaemons::waitFor([&] { return readFile(root / "node.out").find(waiting) != std::string::npos; }, 120.0))
      << readFile(root / "node.out");
  // What the dataset would say of the spec, the live node says too, before it looks for a master.
  const std::string note = "omnicam: note: " + (root / "spec.json").string() +
                           ": size: camera \"fisheye\", a lens camera of 320x240, renders at 96x72 with its intrinsics scaled";
  EXPECT_LT(readFile(root / "node.out").find(note), readFile(root / "node.out").find(waiting)) << readFile(root / "node.out");
  ::kill(node.pid("omnicam ros"), GetParam());
  EXPECT_EQ(node.waitForExit("omnicam ros", 60.0), 0) << readFile(root / "node.out");
  EXPECT_NE(readFile(root / "node.out").find("ros: stopped while waiting for the ROS master: no pose rendered"),
            std::string::npos) << readFile(root / "node.out");
  ::close(port);
  fs::remove_all(root);
}

INSTANTIATE_TEST_SUITE_P(Signals, LiveSensorWaitingForAMaster, ::testing::Values(SIGINT, SIGTERM));

}  // namespace
}  // namespace omnicam
