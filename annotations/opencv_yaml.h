#pragma once
// OpenCV's YAML, written in memory, for the intrinsics files of either camera kind. Included by
// their .cpp files only: OpenCV stays out of the room's interface.
#include <functional>
#include <opencv2/core.hpp>
#include <string>

namespace omnicam {

// What `write` puts in a cv::FileStorage, as YAML text; every number it writes round-trips (%.17g).
inline std::string fileStorageText(const std::function<void(cv::FileStorage&)>& write) {
  cv::FileStorage fs("intrinsics.yaml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  write(fs);
  return fs.releaseAndGetString();
}

}  // namespace omnicam
