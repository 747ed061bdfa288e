#pragma once
// The exact ray of every pixel centre of a camera, as one OpenEXR: the ground truth a
// calibration researcher fits a model to (docs/physical-camera.md). Six float32 channels,
// origin.X/Y/Z (metres) and direction.X/Y/Z (unit), in the viewpoint frame (origin F', robot
// axes); NaN where the camera images nothing.
#include <cstdint>
#include <functional>
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
// Rows are traced in parallel, a band at a time; `onRows(done, total)` is called on the calling
// thread after each band (a physical camera's 16384² table takes minutes).
CameraRayTable cameraRayTable(const Camera& camera, const std::function<void(int rowsDone, int rows)>& onRows = {});
// The table as the OpenEXR file `path` holds it (its name picks nothing but messages' words).
// `onRows(done, total)` as rows are encoded.
std::vector<unsigned char> encodeCameraRayTable(const std::string& path, const CameraRayTable& table,
                                                const std::function<void(int rowsDone, int rows)>& onRows = {});

}  // namespace omnicam
