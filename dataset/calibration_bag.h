#pragma once
// A calibration sequence's images in a ROS 1 bag (docs/calibration.md, "Calibration sequences"):
// DIR/<camera>/calibration/images.bag, every frame's colour image on /<camera>/image_raw (rgb8,
// header.stamp = the frame's timestamp), written once every frame is there (the end of a complete
// run, or a merge) when the spec asks for it (calibration.rosbag).
#include "manifest.h"
#include "safe_files.h"

namespace omnicam {

// Writes each camera's bag when the header asks for one, and lists it among the camera's files
// (key "rosbag"). The frames' PNGs are read inside the folder and must hash to the manifest's.
void writeCalibrationBags(const SafeFolder& dir, DatasetManifest& manifest);

}  // namespace omnicam
