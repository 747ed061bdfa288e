#include "camera_rays.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include <tbb/parallel_for.h>

#include "atomic_file.h"
#include "image.h"
#include "memory_budget.h"

namespace omnicam {

int64_t cameraRayTableBytes(int width, int height) {
  // The table's float32 values, and the OpenEXR encoded from them (at most as large, plus chunks).
  return int64_t{width} * height * static_cast<int64_t>(kCameraRayChannels.size() * sizeof(float)) * 2;
}

CameraRayTable cameraRayTable(const Camera& camera, const std::function<void(int rowsDone, int rows)>& onRows) {
  requireMemory(cameraRayTableBytes(camera.width(), camera.height()),
                "the ray table of " + std::to_string(camera.width()) + "x" + std::to_string(camera.height()) + " pixels");
  CameraRayTable table{camera.width(), camera.height(), {}};
  const size_t channels = kCameraRayChannels.size();
  table.values.assign(static_cast<size_t>(table.width) * table.height * channels, NAN);
  const auto traceRow = [&](int j) {
    for (int i = 0; i < table.width; ++i) {
      const auto ray = camera.generateRay({pixelCentre(i, j)});
      if (!ray) continue;
      float* out = &table.values[(static_cast<size_t>(j) * table.width + i) * channels];
      for (int c = 0; c < 3; ++c) {
        out[c] = static_cast<float>(ray->origin[c]);
        out[3 + c] = static_cast<float>(ray->direction[c]);
      }
    }
  };
  // About a hundred bands: progress often enough, each band (16 rows at least) still work for
  // every thread.
  const int band = std::max(16, table.height / 100);
  for (int first = 0; first < table.height; first += band) {
    const int end = std::min(table.height, first + band);
    tbb::parallel_for(first, end, traceRow);
    if (onRows) onRows(end, table.height);
  }
  return table;
}

std::vector<unsigned char> encodeCameraRayTable(const std::string& path, const CameraRayTable& table,
                                                const std::function<void(int rowsDone, int rows)>& onRows) {
  return encodeDataExr(path, table.width, table.height, kCameraRayChannels, table.values.data(), ExrPrecision::Float, onRows);
}

}  // namespace omnicam
