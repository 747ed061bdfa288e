#pragma once
// Images in a ROS 1 bag (sensor_msgs/Image, rgb8), the input Kalibr reads, written by Debian's
// python3-rosbag (calibration/write_rosbag.py) in a private job folder, streamed: omnicam hands
// the writer one image at a time and copies the bag into place piece by piece, so the bag's size
// never bounds memory (one image does).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "safe_files.h"

namespace omnicam {

struct BagImage {
  std::string topic;    // "/cam0/image_raw"
  std::string frameId;  // header.frame_id
  int64_t stampNs = 0;  // header.stamp, and the record time but at least ROS's TIME_MIN (1 ns)
  uint32_t seq = 0;
  int width = 0, height = 0;
  std::string rgb8;  // width·height·3 bytes, row by row from the top
};

// The bag's images in order, one at a time: nothing when there are no more.
using BagImageSource = std::function<std::optional<BagImage>()>;

struct WrittenBag {
  std::string sha256;
  int64_t bytes = 0;
  int images = 0;
  int64_t largestImageBytes = 0;  // the most omnicam held of the bag at once (one image's rgb8)
  int64_t writerPeakBytes = 0;    // the Python writer's peak resident memory (its ru_maxrss)
};

// Writes the bag of `next`'s images to dir/relative (atomically, unsynced like dataset frames).
// ExternalError when python3-rosbag is missing or fails (its log's tail).
WrittenBag writeImageBag(const SafeFolder& dir, const std::string& relative, const BagImageSource& next);
// ExternalError unless the writer's Python modules import: checked before a run renders anything.
void checkImageBagWriter();

}  // namespace omnicam
