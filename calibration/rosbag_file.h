#pragma once
// Images in a ROS 1 bag (sensor_msgs/Image, rgb8), the input Kalibr reads, written by Debian's
// python3-rosbag (calibration/write_rosbag.py) in a private job folder.
#include <cstdint>
#include <string>
#include <vector>

namespace omnicam {

struct BagImage {
  std::string topic;    // "/cam0/image_raw"
  std::string frameId;  // header.frame_id
  int64_t stampNs = 0;  // header.stamp and the record time
  uint32_t seq = 0;
  int width = 0, height = 0;
  std::string rgb8;  // width·height·3 bytes, row by row from the top
};

// The bag's bytes. ExternalError when python3-rosbag is missing or fails (its log's tail).
std::string imageBag(const std::vector<BagImage>& images);
// ExternalError unless the writer's Python modules import: checked before a run renders anything.
void checkImageBagWriter();

}  // namespace omnicam
