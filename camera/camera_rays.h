#pragma once
// The exact ray of every pixel centre of a camera, as one OpenEXR: the ground truth a
// calibration researcher fits a model to (docs/physical-camera.md). Six float32 channels,
// origin.X/Y/Z (metres) and direction.X/Y/Z (unit), in the viewpoint frame (origin F', robot
// axes); NaN where the camera images nothing.
#include <cstdint>
#include <string>
#include <vector>

#include "camera.h"

namespace omnicam {

inline const std::vector<std::string> kCameraRayChannels = {"origin.X",    "origin.Y",    "origin.Z",
                                                            "direction.X", "direction.Y", "direction.Z"};

struct CameraRayTable {
  int width = 0, height = 0;
  std::vector<float> values;  // row-major, kCameraRayChannels.size() per pixel
};

// What making and writing a table takes: 48 bytes a pixel (2 × 6 float32 values).
int64_t cameraRayTableBytes(int width, int height);
// MemoryShortage (memory_budget.h) before anything is allocated when the machine cannot hold it.
CameraRayTable cameraRayTable(const Camera& camera);
// Writes the table atomically; OutputError naming `path` if it cannot.
void writeCameraRayTable(const std::string& path, const CameraRayTable& table);

}  // namespace omnicam
