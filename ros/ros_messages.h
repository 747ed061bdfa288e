#pragma once
// The ROS messages omnicam's live sensor (issue #49) sends and receives, in plain C++17 types.
// ROS 1's generated message headers do not compile as C++20 (they use std::allocator<void>::rebind,
// removed in C++20), so only ros_transport.cpp, built as C++17, includes them; the rest of
// omnicam talks to ROS through these structs.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace omnicam::ros1 {

// A ROS time: seconds and nanoseconds since the epoch.
struct Stamp {
  uint32_t sec = 0;
  uint32_t nsec = 0;
  double seconds() const { return sec + nsec * 1e-9; }
};

// nav_msgs/Odometry: the pose of `childFrame` in `frame`, and its twist in `childFrame`.
struct Odometry {
  Stamp stamp;
  std::string frame, childFrame;
  double position[3] = {0, 0, 0};
  double orientationXyzw[4] = {0, 0, 0, 1};
  double linear[3] = {0, 0, 0};
  double angular[3] = {0, 0, 0};
};

// sensor_msgs/Image, row-major, `step` bytes a row.
struct Image {
  Stamp stamp;
  std::string frame;
  uint32_t width = 0, height = 0, step = 0;
  std::string encoding;  // "rgb8", "32FC1", "16UC1"
  std::vector<uint8_t> data;
};

// sensor_msgs/CameraInfo (annotations/ros_camera_info.h says what each model's holds).
struct CameraInfo {
  Stamp stamp;
  std::string frame;
  uint32_t width = 0, height = 0;
  std::string distortionModel;
  std::vector<double> d;
  std::array<double, 9> k{}, r{};
  std::array<double, 12> p{};
};

// geometry_msgs/TransformStamped: `child`'s frame in `parent`'s.
struct Transform {
  std::string parent, child;
  double translation[3] = {0, 0, 0};
  double rotationXyzw[4] = {0, 0, 0, 1};
};

// diagnostic_msgs/DiagnosticStatus, published alone in a DiagnosticArray on /diagnostics.
struct Diagnostic {
  enum Level : int8_t { Ok = 0, Warn = 1, Error = 2 };
  Level level = Ok;
  std::string name, message, hardwareId;
  std::vector<std::pair<std::string, std::string>> values;
};

using OdometryHandler = std::function<void(const Odometry&)>;
// A transform tf could not give at `stamp` (a gap in the tree, an extrapolation): why.
using GapHandler = std::function<void(const Stamp& stamp, const std::string& why)>;

}  // namespace omnicam::ros1
