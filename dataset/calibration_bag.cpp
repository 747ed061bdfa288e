#include "calibration_bag.h"

#include <cmath>
#include <cstring>

#include "annotation_files.h"
#include "dataset_spec.h"
#include "errors.h"
#include "image.h"
#include "number_format.h"
#include "output_kinds.h"
#include "rosbag_file.h"
#include "sha256.h"

namespace omnicam {

using nlohmann::json;

namespace {

// A frame's PNG as rgb8 rows, top to bottom or (`flip`) bottom to top.
BagImage bagImage(const SafeFolder& dir, const FileRecord& file, const std::string& camera, bool flip, int index, double intervalS) {
  BagImage image;
  std::vector<unsigned char> rgb;
  {
    const std::string bytes = checkedBytes(dir, file);
    rgb = readRgb8Codes(bytes, showPath(dir.path()) + ": " + quote(file.path), image.width, image.height);
  }
  image.topic = "/" + camera + "/image_raw";
  image.frameId = camera;
  image.stampNs = frameTimestampNs(index, intervalS);  // the frame's time, as EuRoC names its images
  image.seq = static_cast<uint32_t>(index);
  const size_t row = static_cast<size_t>(image.width) * 3;
  image.rgb8.resize(row * static_cast<size_t>(image.height));
  for (int y = 0; y < image.height; ++y)
    std::memcpy(image.rgb8.data() + static_cast<size_t>(flip ? image.height - 1 - y : y) * row, rgb.data() + static_cast<size_t>(y) * row, row);
  return image;
}

}  // namespace

void writeCalibrationBag(const SafeFolder& dir, DatasetManifest& manifest) {
  // Looked up, not made: a dataset without a calibration sequence has no "calibration" field.
  const auto found = manifest.header.find("calibration");
  if (found == manifest.header.end() || !found->is_object() || found->value("rosbag", json(false)) != json(true)) return;
  json& calibration = *found;
  const json intervalField = manifest.header.value("settings", json::object()).value("frame_interval_s", json());
  // A manifest is untrusted (a merge reads a shard's): the spec's bounds, so that every stamp
  // (frame × interval, in ns) fits in 64 bits.
  if (!intervalField.is_number() || !(intervalField.get<double>() * 1e9 >= 1.0) ||
      !(intervalField.get<double>() <= limits::kMaxFrameIntervalSeconds))
    throw InputError(showPath(dir.path()) + ": manifest: settings.frame_interval_s must be a number from 1 ns to " +
                     shortNumber(limits::kMaxFrameIntervalSeconds) + " s for the ROS bag");
  const double interval = intervalField.get<double>();
  struct BagCamera {
    std::string name;
    bool flip;  // a mirror camera's image is a mirror image: Kalibr's omni model needs it flipped
  };
  std::vector<BagCamera> cameras;
  for (const json& camera : manifest.header.at("cameras"))
    cameras.push_back({camera.at("name").get<std::string>(), !camera.value("rig", json::object()).contains("lens")});
  // Frame by frame, each camera's image in turn: one image in memory at a time.
  auto frame = manifest.frames.begin();
  size_t next = 0;
  const WrittenBag bag = writeImageBag(dir, kKalibrBagPath, [&]() -> std::optional<BagImage> {
    if (frame == manifest.frames.end()) return std::nullopt;
    const auto& [index, record] = *frame;
    const BagCamera& camera = cameras[next];
    const auto c = record.cameras.find(camera.name);
    const FileRecord* file = c == record.cameras.end() ? nullptr : c->second.file(kColourOutput);
    if (!file)
      throw InputError(showPath(dir.path()) + ": frame " + std::to_string(index) + " camera " + quote(camera.name) + " has no colour image");
    BagImage image = bagImage(dir, *file, camera.name, camera.flip, index, interval);
    if (++next == cameras.size()) next = 0, ++frame;
    return image;
  });
  calibration["files"]["rosbag"] = {{"path", kKalibrBagPath}, {"sha256", bag.sha256}};
}

}  // namespace omnicam
