#include "calibration_bag.h"

#include <cmath>
#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "annotation_files.h"
#include "errors.h"
#include "output_kinds.h"
#include "rosbag_file.h"
#include "sha256.h"

namespace omnicam {

using nlohmann::json;

namespace {

// A frame's PNG as rgb8 rows.
BagImage bagImage(const SafeFolder& dir, const FileRecord& file, const std::string& camera, int index, double intervalS) {
  const std::string bytes = checkedBytes(dir, file);
  const cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8UC1, const_cast<char*>(bytes.data()));
  cv::Mat bgr = cv::imdecode(encoded, cv::IMREAD_COLOR);
  if (bgr.empty() || bgr.depth() != CV_8U)
    throw InputError(showPath(dir.path()) + ": " + quote(file.path) + ": not an 8-bit PNG (a ROS bag holds 8-bit images)");
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  BagImage image;
  image.topic = "/" + camera + "/image_raw";
  image.frameId = camera;
  image.stampNs = eurocTimestampNs(index, intervalS);  // the frame's time, as EuRoC names its images
  image.seq = static_cast<uint32_t>(index);
  image.width = rgb.cols, image.height = rgb.rows;
  image.rgb8.resize(static_cast<size_t>(rgb.cols) * rgb.rows * 3);
  for (int y = 0; y < rgb.rows; ++y)
    std::memcpy(image.rgb8.data() + static_cast<size_t>(y) * rgb.cols * 3, rgb.ptr(y), static_cast<size_t>(rgb.cols) * 3);
  return image;
}

}  // namespace

void writeCalibrationBags(const SafeFolder& dir, DatasetManifest& manifest) {
  const json calibration = manifest.header.value("calibration", json::object());
  if (!calibration.is_object() || calibration.value("rosbag", json(false)) != json(true)) return;
  const json intervalField = manifest.header.value("settings", json::object()).value("frame_interval_s", json());
  if (!intervalField.is_number() || !(intervalField.get<double>() * 1e9 >= 1.0))
    throw InputError(showPath(dir.path()) + ": manifest: settings.frame_interval_s must be a number of at least 1 ns for the ROS bag");
  const double interval = intervalField.get<double>();
  for (json& camera : manifest.header.at("cameras")) {
    const std::string name = camera.at("name").get<std::string>();
    std::vector<BagImage> images;
    for (const auto& [index, frame] : manifest.frames) {
      const auto c = frame.cameras.find(name);
      const FileRecord* file = c == frame.cameras.end() ? nullptr : c->second.file(kColourOutput);
      if (!file)
        throw InputError(showPath(dir.path()) + ": frame " + std::to_string(index) + " camera " + quote(name) + " has no colour image");
      images.push_back(bagImage(dir, *file, name, index, interval));
    }
    const std::string bag = imageBag(images);
    const std::string relative = name + "/calibration/images.bag";
    dir.writeFile(relative, bag, Durability::Unsynced);
    camera["files"]["rosbag"] = {{"path", relative}, {"sha256", sha256OfBytes(bag)}};
  }
}

}  // namespace omnicam
