#pragma once
// The ROS messages omnicam's live sensor (issue #49) sends and receives, in plain C++17 types.
// ROS 1's generated message headers do not compile as C++20 (they use std::allocator<void>::rebind,
// removed in C++20), so only ros_transport.cpp, built as C++17, includes them; the rest of
// omnicam talks to ROS through these structs.
#include <array>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace omnicam::ros1 {

// A pose's or transform's stamp more than this after ROS time now is refused (once ROS time is not
// zero: under simulated time, after /clock's first message). A clock that far ahead would hold
// every later pose back (poses only go forward; tf2 drops data older than its newest by 10 s).
constexpr double kMostStampAheadSeconds = 60.0;

// A ROS time: seconds and nanoseconds since the epoch.
struct Stamp {
  uint32_t sec = 0;
  uint32_t nsec = 0;
  double seconds() const { return sec + nsec * 1e-9; }
  int64_t nanoseconds() const { return int64_t{sec} * 1000000000 + nsec; }
  static Stamp ofNanoseconds(int64_t ns) { return {static_cast<uint32_t>(ns / 1000000000), static_cast<uint32_t>(ns % 1000000000)}; }
  bool zero() const { return sec == 0 && nsec == 0; }
  bool operator==(const Stamp& o) const { return sec == o.sec && nsec == o.nsec; }
  bool operator<(const Stamp& o) const { return nanoseconds() < o.nanoseconds(); }
};

// "sec.nnnnnnnnn", as messages show a stamp.
inline std::string stampText(const Stamp& stamp) {
  char text[32];
  std::snprintf(text, sizeof text, "%u.%09u", stamp.sec, stamp.nsec);
  return text;
}

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

// What becomes of the poses asked of tf (Transport::subscribeTransform).
struct TransformHandlers {
  OdometryHandler pose;  // the pose at a stamp asked for, once the tree reaches it
  // A stamp the tree did not reach (a gap, a parent never sent) in time, or before it reached a
  // later one: tf's reason.
  std::function<void(const Stamp& stamp, const std::string& why)> gap;
};

}  // namespace omnicam::ros1
