#pragma once
// A camera's intrinsics as ROS 1's sensor_msgs/CameraInfo holds them (the live sensor's
// camera_info, docs/ros.md), in OpenCV's pixel convention like the intrinsics files:
// - a mirror camera: distortion_model "omnidirectional", D = [ξ, k1, k2, p1, p2], K of the Mei
//   model (γy < 0, as opencv.yaml) — the de-facto convention of omnidirectional ROS drivers, as
//   ROS has no name of its own for it;
// - Kannala–Brandt and the equidistant f-θ lens: "equidistant", D = [k1, k2, k3, k4] (cv::fisheye);
// - the pinhole: "plumb_bob", D = [k1, k2, p1, p2, k3];
// - other lenses (double sphere, extended unified, the other f-θ lenses, the panorama):
//   "omnicam/<model>", no K or D, and the camera's own intrinsics (its sidecar's) as JSON.
// R is the identity and P = [K | 0] where there is a K.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "camera.h"

namespace omnicam {

struct RosCameraInfo {
  uint32_t width = 0, height = 0;
  std::string distortionModel;
  std::vector<double> d;
  std::array<double, 9> k{}, r{};
  std::array<double, 12> p{};
  std::string intrinsicsJson;  // only for a model ROS has no name for
};

RosCameraInfo rosCameraInfoOf(const Camera& camera);

}  // namespace omnicam
