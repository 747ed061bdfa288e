#pragma once
// Calibrating a camera of a calibration sequence (docs/calibration.md, "Calibrating a dataset's
// camera"): the target's corners in its frames — found in the images by the detectors a
// calibration tool uses, or the exact ones the dataset records — fitted by cv::omnidir::calibrate
// (Mei's unified model), then measured where a user cannot measure: against the camera's true
// rays, on points it never saw. What `omnicam calibrate` prints.
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "omnidir_fit.h"

namespace omnicam {

struct DatasetCalibrationOptions {
  std::string camera;          // empty: the dataset's first mirror camera
  bool exactCorners = false;   // the recorded exact corners instead of the detectors'
  bool fixDistortion = false;  // k1, k2, p1, p2 held at zero
  bool checkHashes = true;     // each file read must hash to the manifest's SHA-256
  std::vector<double> heldOutDistancesM{0.5, 1.0, 5.0};
  std::function<void(int done, int total)> progress;  // after each frame's corners are found
};

struct DatasetCalibration {
  std::string camera;
  std::string target;  // the calibration target's name in the scene
  int frames = 0;      // frames of the sequence
  int views = 0;       // frames with the 4 corners a view needs, given to the calibration
  int corners = 0;     // corners in those views
  // Detected corners against the exact ones of the same index, over every frame (detected only).
  int cornersDetected = 0;
  double detectionMedianPx = 0.0, detectionMaxPx = 0.0;
  OmnidirCalibration fit;
  std::vector<HeldOutError> heldOut;  // once converged: at each distance asked for
  nlohmann::json truth;               // the camera's intrinsics as the manifest states them
  int width = 0, height = 0;          // the images'
};

// InputError for a folder that is not a calibration sequence, a camera it does not have or that is
// not a mirror camera (the unified model here is the catadioptric one), an unfinished sequence
// (detection needs every frame's image), or files that are not as their manifest says; the calibration's own failure (too few views, OpenCV's
// initialisation) is the result's fit.failure.
DatasetCalibration calibrateDatasetCamera(const std::string& dir, const DatasetCalibrationOptions& options);

}  // namespace omnicam
